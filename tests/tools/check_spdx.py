#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Every source file names its licence on an SPDX line, so a file copied out of the tree keeps it:
GPL-3.0-or-later under apps/blender/silk_blender/ (Blender add-ons are GPL), MIT everywhere else
(LICENSE). The line is the file's first, after a shebang and a Python coding line, in the file's
comment syntax: `// SPDX-License-Identifier: MIT` (C++; `/* ... */` in C files and in headers
written in C comments, such as silk.h), `# SPDX-License-Identifier: MIT` (Python, shell, CMake).

  check_spdx.py [ROOT]          fails naming each source file without the right line
  check_spdx.py --fix [ROOT]    inserts the line where it is missing, corrects a wrong licence
  check_spdx.py --selftest      the check and --fix on scratch files (the check can fail)

Source files: *.c, *.cc, *.cpp, *.h, *.hpp, *.py, *.sh, *.cmake, *.cmake.in, CMakeLists.txt, as
git lists them (every file below ROOT outside build folders when ROOT is not a checkout). Data
(meshes, token lists, models, docs), generated files (a "DO NOT EDIT" in their first lines) and
third-party files (THIRD_PARTY) are not sources.
"""

import pathlib
import re
import subprocess
import sys
import tempfile

GPL_DIRS = ("apps/blender/silk_blender/",)
THIRD_PARTY = ()  # repository-relative paths of vendored files that keep their own headers
SLASH = (".cc", ".cpp", ".hpp")
HASH = (".py", ".sh", ".cmake")
TAG = "SPDX-License-Identifier:"
CODING = re.compile(r"^[ \t\f]*#.*?coding[:=][ \t]*[-\w.]+")
SKIP_DIRS = {".git", ".deps", "__pycache__", "node_modules"}


def licence_of(rel):
    return "GPL-3.0-or-later" if rel.startswith(GPL_DIRS) else "MIT"


def comment_style(rel, lines):
    """'//', '/*' or '#' for a source file, None for anything else."""
    name = rel.rsplit("/", 1)[-1]
    if name == "CMakeLists.txt" or name.endswith(".cmake.in") or name.endswith(HASH):
        return "#"
    if name.endswith(".c"):
        return "/*"
    if name.endswith(".h"):
        first = next((l for l in lines if l.strip()), "")
        return "/*" if first.lstrip().startswith("/*") else "//"
    if name.endswith(SLASH):
        return "//"
    return None


def spdx_line(style, licence):
    if style == "/*":
        return f"/* {TAG} {licence} */"
    return f"{style} {TAG} {licence}"


def header_end(lines):
    """Index of the first line after a shebang and a Python coding line (where the SPDX line goes)."""
    i = 1 if lines and lines[0].startswith("#!") else 0
    if i < len(lines) and i < 2 and CODING.match(lines[i]):
        i += 1
    return i


def is_generated(lines):
    return any("DO NOT EDIT" in l for l in lines[:5])


def examine(rel, text):
    """(problem or None, fixed text or None) for one file's text."""
    lines = text.splitlines(keepends=True)
    bare = [l.rstrip("\r\n") for l in lines]
    style = comment_style(rel, bare)
    if style is None or is_generated(bare) or rel in THIRD_PARTY:
        return None, None
    want = spdx_line(style, licence_of(rel))
    at = header_end(bare)
    existing = [i for i, l in enumerate(bare[: at + 3]) if TAG in l]
    if at < len(bare) and bare[at] == want and len(existing) == 1:
        return None, None
    newline = "\r\n" if lines and lines[0].endswith("\r\n") else "\n"
    for i in reversed(existing):
        del lines[i]
    lines.insert(at, want + newline)
    if existing:
        found = bare[existing[0]].strip()
        return f"{rel}: '{found}' where '{want}' belongs (line {at + 1})", "".join(lines)
    return f"{rel}: no '{want}' (line {at + 1})", "".join(lines)


def source_files(root):
    try:
        out = subprocess.run(["git", "-C", str(root), "ls-files", "-z"], check=True, capture_output=True).stdout
        return sorted(p for p in out.decode("utf-8").split("\0") if p)
    except (OSError, subprocess.CalledProcessError):
        return sorted(
            p.relative_to(root).as_posix()
            for p in root.rglob("*")
            if p.is_file()
            and not any(part in SKIP_DIRS or part.startswith("build") for part in p.relative_to(root).parts[:-1])
        )


def run(root, fix):
    bad, checked = [], 0
    for rel in source_files(root):
        path = root / rel
        if not path.is_file() or path.is_symlink():
            continue
        try:
            text = path.read_text(encoding="utf-8")
        except UnicodeDecodeError:
            continue  # binary data
        problem, fixed = examine(rel, text)
        checked += comment_style(rel, text.splitlines()) is not None
        if problem:
            bad.append(problem)
            if fix:
                path.write_text(fixed, encoding="utf-8", newline="")
    return bad, checked


def selftest():
    cases = {  # file -> (text, the text --fix must give)
        "tool.py": (
            '#!/usr/bin/env python3\n"""Doc."""\n',
            '#!/usr/bin/env python3\n# SPDX-License-Identifier: MIT\n"""Doc."""\n',
        ),
        "enc.py": (
            "# -*- coding: utf-8 -*-\nx = 1\n",
            "# -*- coding: utf-8 -*-\n# SPDX-License-Identifier: MIT\nx = 1\n",
        ),
        "a.cpp": ("// Why a exists.\nint a;\n", "// SPDX-License-Identifier: MIT\n// Why a exists.\nint a;\n"),
        "c.h": ("/* A C header. */\n", "/* SPDX-License-Identifier: MIT */\n/* A C header. */\n"),
        "apps/blender/silk_blender/ops.py": (
            "# SPDX-License-Identifier: MIT\nimport bpy\n",
            "# SPDX-License-Identifier: GPL-3.0-or-later\nimport bpy\n",
        ),
        "s.sh": ("#!/bin/sh\necho\n", "#!/bin/sh\n# SPDX-License-Identifier: MIT\necho\n"),
        "CMakeLists.txt": ("project(x)\n", "# SPDX-License-Identifier: MIT\nproject(x)\n"),
        "ok.cpp": ("// SPDX-License-Identifier: MIT\nint b;\n", None),
        "gen.h": ("// Generated from x.json. DO NOT EDIT.\n", None),
        "notes.txt": ("text\n", None),
        "mesh.obj": ("v 0 0 0\n", None),
    }
    errors = []
    with tempfile.TemporaryDirectory() as tmp:
        root = pathlib.Path(tmp)
        for rel, (text, _) in cases.items():
            (root / rel).parent.mkdir(parents=True, exist_ok=True)
            (root / rel).write_text(text)
        bad, _ = run(root, fix=False)
        flagged = {b.split(":")[0] for b in bad}
        want = {rel for rel, (_, fixed) in cases.items() if fixed is not None}
        if flagged != want:
            errors.append(f"check flagged {sorted(flagged)}, expected {sorted(want)}")
        run(root, fix=True)
        for rel, (text, fixed) in cases.items():
            got = (root / rel).read_text()
            if got != (fixed if fixed is not None else text):
                errors.append(f"--fix made {rel!r} {got!r}")
        again, _ = run(root, fix=False)
        if again:
            errors.append(f"after --fix the check still reports {again}")
    print(
        "selftest:",
        "ok (missing, wrong and misplaced lines caught and fixed; data and generated files left alone)"
        if not errors
        else "; ".join(errors),
    )
    return 1 if errors else 0


def main(argv):
    args = argv[1:]
    if args == ["--selftest"]:
        return selftest()
    fix = args[:1] == ["--fix"]
    args = args[1:] if fix else args
    if len(args) > 1 or any(a.startswith("-") for a in args):
        print(__doc__)
        return 2
    root = pathlib.Path(args[0] if args else ".").resolve()
    bad, checked = run(root, fix)
    for b in bad:
        print(b)
    verb = "fixed" if fix else "without the right SPDX line"
    print(f"check_spdx: {checked} source files under {root}, {len(bad)} {verb}")
    return 1 if bad and not fix else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
