#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Keeps the front-page documents honest: every repository path that README.md and
engine/README.md name exists, every engine folder is named in engine/README.md (or in the README
of its layer), and the README stays short enough to read in two minutes.

  check_docs.py ROOT          check the checkout at ROOT; exit 1 listing every problem
  check_docs.py --selftest    the checks on a planted tree (a missing path, an unnamed folder,
                              a long README) must fail, and a clean tree must pass

A "path" is a Markdown link target or a back-quoted word that starts with one of the repository's
top-level folders (or is a top-level file) and holds no spaces, wildcards or placeholders; links
to other sites, anchors and paths outside the repository (`../shared/...`) are not checked.
"""

import pathlib
import re
import sys
import tempfile

README_MAX_LINES = 150
LINK = re.compile(r"\]\(([^)\s]+)\)")
CODE = re.compile(r"`([^`\s]+)`")
PLACEHOLDER = re.compile(r"[*<>{}|$]|\.\.\.|XXX|NAME|/N$")


def named_paths(text, base, root):
    """The repository paths a Markdown text names, resolved against its folder `base`."""
    top = {p.name for p in root.iterdir() if not p.name.startswith(".")}
    found = set()
    for target in LINK.findall(text):
        if re.match(r"^[a-z]+:", target) or target.startswith("#"):
            continue
        found.add(((base / target.split("#")[0]).resolve(), target))
    for word in CODE.findall(text):
        word = word.rstrip(".,:;)")
        if PLACEHOLDER.search(word) or word.startswith(("../", "/", "-")):
            continue
        first = word.split("/")[0]
        if "/" in word and first in top:
            found.add(((root / word).resolve(), word))
        elif "/" in word and (base / first).exists() and base != root:
            found.add(((base / word).resolve(), word))
    return found


def check(root):
    root = pathlib.Path(root).resolve()
    problems = []
    for doc in ("README.md", "engine/README.md"):
        path = root / doc
        text = path.read_text(encoding="utf-8")
        for resolved, shown in sorted(named_paths(text, path.parent, root)):
            if root in resolved.parents or resolved == root:
                if not resolved.exists():
                    problems.append(f"{doc}: names `{shown}`, which does not exist")
    lines = (root / "README.md").read_text(encoding="utf-8").count("\n")
    if lines > README_MAX_LINES:
        problems.append(f"README.md: {lines} lines, more than {README_MAX_LINES}")
    engine_doc = (root / "engine/README.md").read_text(encoding="utf-8")
    for folder in sorted(p for p in (root / "engine").rglob("*") if p.is_dir()):
        rel = folder.relative_to(root / "engine").as_posix()
        if "__pycache__" in rel:
            continue
        layer_readme = root / "engine" / rel.split("/")[0] / "README.md"
        texts = engine_doc + (layer_readme.read_text(encoding="utf-8") if layer_readme.exists() else "")
        leaf = rel.split("/")[-1]
        if not re.search(r"(^|[`/ ])" + re.escape(leaf) + r"/", texts):
            problems.append(f"engine/{rel}/: named neither in engine/README.md nor in its layer's README")
    return problems


def selftest():
    with tempfile.TemporaryDirectory() as tmp:
        root = pathlib.Path(tmp)
        (root / "engine/core").mkdir(parents=True)
        (root / "docs").mkdir()
        (root / "docs/a.md").write_text("x\n")
        (root / "engine/README.md").write_text("`core/`: the base.\n")
        (root / "README.md").write_text("See [a](docs/a.md) and `engine/core`.\n")
        if check(root):
            print("selftest: a clean tree was refused:", check(root))
            return 1
        plants = {
            "a missing link target": lambda: (root / "README.md").write_text("See [b](docs/b.md).\n"),
            "a missing code path": lambda: (root / "README.md").write_text("See `docs/c.md`.\n"),
            "an unnamed folder": lambda: (root / "engine/mesh").mkdir(),
            "a long README": lambda: (root / "README.md").write_text("line\n" * (README_MAX_LINES + 1)),
        }
        for what, plant in plants.items():
            (root / "README.md").write_text("See [a](docs/a.md).\n")
            if (root / "engine/mesh").exists():
                (root / "engine/mesh").rmdir()
            plant()
            if not check(root):
                print(f"selftest: {what} was not caught")
                return 1
    print(
        "selftest: ok (a clean tree passes; a missing link, a missing code path, an unnamed folder and a long README fail)"
    )
    return 0


def main(argv):
    if argv[1:] == ["--selftest"]:
        return selftest()
    if len(argv) != 2:
        print(__doc__)
        return 2
    problems = check(argv[1])
    for p in problems:
        print(p)
    print(f"check_docs: {len(problems)} problem(s)")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
