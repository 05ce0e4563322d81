#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Counts the lines of every function in the C++ and Python sources, so that the style rule
"a function fits on a screen" is checked by a test rather than by memory.

  function_census.py [--limit N] [--fail] PATH...   every function of >= N lines (default 80),
                                                    longest first; --fail: exit 1 if any
  function_census.py --selftest                     the C++ and Python counters on known code

A C++ function is a brace block opened at namespace or class scope whose header has a parameter
list (control statements, initialisers and type bodies are not functions); its length runs from
the header's first line to the closing brace. Lambdas and local classes count toward the function
that holds them. A Python function is a def (methods and nested defs count on their own). Data
tables are exempt where the function is marked with a comment `// census: data table` on the
line above its header.
"""

import ast
import pathlib
import re
import sys

CPP = (".cpp", ".cc", ".h", ".hpp")
NOT_FUNCTION = re.compile(
    r"^\s*(if|for|while|switch|catch|do|else|try|return)\b|\b(namespace|class|struct|union|enum)\b[^()]*$|=\s*$|\[\]\s*$"
)
EXEMPT = "census: data table"


def strip_cpp(text):
    """Blanks comments, string and char literals (keeping newlines and the exempt marker)."""
    out, i, n = [], 0, len(text)
    while i < n:
        c = text[i]
        if text.startswith("//", i):
            j = text.find("\n", i)
            j = n if j < 0 else j
            out.append(" EXEMPT_MARK " if EXEMPT in text[i:j] else " " * (j - i))
            i = j
        elif text.startswith("/*", i):
            j = text.find("*/", i + 2)
            j = n if j < 0 else j + 2
            out.append(re.sub(r"[^\n]", " ", text[i:j]))
            i = j
        elif text.startswith('R"', i):
            m = re.match(r'R"([^(]*)\(', text[i:])
            end = text.find(")" + m.group(1) + '"', i) if m else -1
            j = n if end < 0 else end + len(m.group(1)) + 2
            out.append(re.sub(r"[^\n]", " ", text[i:j]))
            i = j
        elif c in "\"'" and not (c == "'" and i and text[i - 1].isalnum() and text[i + 1 : i + 2].isdigit()):
            j = i + 1
            while j < n and text[j] != c and text[j] != "\n":
                j += 2 if text[j] == "\\" else 1
            out.append(" " * (min(j + 1, n) - i))
            i = j + 1
        else:
            out.append(c)
            i += 1
    return "".join(out)


def cpp_functions(text):
    """Yields (name, first line, line count, exempt) for each function body in C++ source."""
    # Preprocessor lines blanked, a macro continued with a backslash over all its lines.
    code = re.sub(r"(?m)^[ \t]*#(?:.*\\\n)*.*$", lambda m: re.sub(r"[^\n]", " ", m.group(0)), strip_cpp(text))
    stack = []  # (kind, name, first line, exempt) per open brace
    header_start = 0  # offset where the current statement/header began
    for pos, ch in enumerate(code):
        if ch in ";":
            header_start = pos + 1
        elif ch == "{":
            header = code[header_start:pos]
            outer = all(k in ("scope", "type") for k, *_ in stack)
            kind = "block"
            if outer:
                flat = " ".join(header.split())
                if re.search(r"\b(namespace|extern\s+\"?C?)\b", flat) and "(" not in flat:
                    kind = "scope"
                elif re.search(r"\b(class|struct|union|enum)\b", flat) and "(" not in flat.split(":")[0]:
                    kind = "type"
                elif "(" in flat and ")" in flat and not NOT_FUNCTION.search(flat) and "=" not in flat.split("(")[0]:
                    kind = "function"
                elif not flat or flat.startswith("extern"):
                    kind = "scope"
            if kind == "function":
                name = re.findall(r"([A-Za-z_~][\w:~<>]*)\s*\(", flat)
                exempt = "EXEMPT_MARK" in header
                body = header.replace("EXEMPT_MARK", "           ")
                first = code.count("\n", 0, header_start + len(body) - len(body.lstrip())) + 1
                stack.append((kind, name[0] if name else "?", first, exempt))
            else:
                stack.append((kind, None, 0, False))
            header_start = pos + 1
        elif ch == "}":
            if stack:
                kind, name, first, exempt = stack.pop()
                if kind == "function":
                    yield name, first, code.count("\n", 0, pos) + 1 - first + 1, exempt
            header_start = pos + 1


def py_functions(text):
    for node in ast.walk(ast.parse(text)):
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
            first = min([node.lineno] + [d.lineno for d in node.decorator_list])
            yield node.name, first, node.end_lineno - first + 1, False


def census(paths):
    rows = []
    for root in paths:
        root = pathlib.Path(root)
        files = [root] if root.is_file() else sorted(root.rglob("*"))
        for f in files:
            if "__pycache__" in f.parts or not f.is_file():
                continue
            text = f.read_text(encoding="utf-8", errors="replace")
            if f.suffix in CPP:
                rows += [(n, str(f), name, line, ex) for name, line, n, ex in cpp_functions(text)]
            elif f.suffix == ".py":
                rows += [(n, str(f), name, line, ex) for name, line, n, ex in py_functions(text)]
    return sorted(rows, key=lambda r: (-r[0], r[1], r[3]))


def selftest():
    cpp = (
        '#define TWO(x) \\\n  F(x) "(" F(x)\n'
        "namespace a {\nstruct S {\n  int f(int x) const {\n    if (x) {\n      return 1;\n    }\n"
        '    return 2;\n  }\n};\nint g() {\n  auto l = [] { return "}"; };\n  return l()[0];\n}\n'
        "// census: data table\nconst int* Table() {\n  static const int t[] = {1, 2};\n  return t;\n}\n}\n"
    )
    got = [(name, line, n, ex) for name, line, n, ex in cpp_functions(cpp)]
    want = [("f", 5, 6, False), ("g", 12, 4, False), ("Table", 17, 4, True)]
    py = "def a():\n    def b():\n        return 1\n    return b\n"
    got_py = sorted((name, line, n) for name, line, n, _ in py_functions(py))
    ok = got == want and got_py == [("a", 1, 4), ("b", 2, 2)]
    print("selftest", "passed" if ok else f"FAILED: {got} {got_py}")
    return 0 if ok else 1


def main(argv):
    if argv[:1] == ["--selftest"]:
        return selftest()
    limit, fail, paths = 80, False, []
    it = iter(argv)
    for a in it:
        if a == "--limit":
            limit = int(next(it))
        elif a == "--fail":
            fail = True
        else:
            paths.append(a)
    rows = census(paths)
    long_rows = [r for r in rows if r[0] >= limit and not r[4]]
    for n, f, name, line, _ in long_rows:
        print(f"{n:5d}  {f}:{line}  {name}")
    exempt = [r for r in rows if r[0] >= limit and r[4]]
    for n, f, name, line, _ in exempt:
        print(f"{n:5d}  {f}:{line}  {name}  (data table, exempt)")
    print(f"{len(rows)} functions, {len(long_rows)} of >= {limit} lines")
    return 1 if fail and long_rows else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
