#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Enforces the engine's layering: a lower layer never includes a higher one.
Order: core -> io -> mesh -> tokenizer -> decoder -> kernels -> runtime -> capi (the C API sees all).

  check_layers.py ENGINE_DIR            the layer order inside engine/
  check_layers.py --apps APPS_DIR       silkgen, silktok and common/ (sources both build in)
                                        include nothing of libsilk but the public headers
                                        (silk/silk.h, silk/silk.hpp): every #include "..." is one
                                        of those or a file of the apps' own (e.g. "../common/x.h")
  check_layers.py --apps-selftest       the apps check on a scratch app that includes
                                        "tokenizer/tokenizer.h" must fail (the check can fail)
  check_layers.py --folders ENGINE_DIR  no engine folder holds more than 40 source files
                                        directly (a larger one wants sub-folders by concern)
  check_layers.py --private-selftest    the engine check on a scratch engine whose decoder
                                        includes a tokenizer-private header must fail
  check_layers.py --stages ENGINE_DIR   the stage order inside each layer that has sub-folders
  check_layers.py --python-stages PACKAGE_DIR README
                                        the same for a Python package's sub-packages (imports)
  check_layers.py --stages-selftest     the stage check on a scratch layer with a planted back
                                        include (and a planted back import) must fail
Headers in PRIVATE belong to their layer alone (docs/mesh_types.md): no other layer includes them.

Stage order. A layer with sub-folders (stages) names their order in its README, on one line:
    Stage order: `cleanup -> manifold -> layering`        (`a | b` for peers: neither sees the other)
A file of a stage may include files of its own stage and of earlier ones, never of a later stage
or a peer. Files directly in the layer folder belong to no stage (the layer's shared types and its
front door): a stage file may include one only if every stage that file reaches through its own
includes (transitively) is the includer's stage or an earlier one.
"""

import ast
import pathlib
import re
import sys
import tempfile

ORDER = ["core", "io", "mesh", "tokenizer", "decoder", "kernels", "runtime", "capi"]
APPS = ["silkgen", "silktok", "common"]  # common/: sources both tools build in
PUBLIC = {"silk/silk.h", "silk/silk.hpp"}
SOURCES = (".h", ".hpp", ".cpp", ".cc")
# Layer-internal headers: the tokenizer's encoder mesh (TokenizerProcessedMesh) and the encoder
# stages on it. Tests of the layer may include them; other layers may not.
PRIVATE = {"tokenizer/processed_mesh.h", "tokenizer/processed_encoder.h"}
quoted = re.compile(r'^\s*#\s*include\s*"([^"]+)"')


def check_engine(root):
    inc = re.compile(r'^\s*#\s*include\s*"(([a-z_]+)/[^"]*)"')
    bad = []
    for layer in ORDER:
        for f in sorted((root / layer).rglob("*")):
            if f.suffix not in SOURCES:
                continue
            for n, line in enumerate(f.read_text(encoding="utf-8").splitlines(), 1):
                m = inc.match(line)
                if m and m.group(2) in ORDER and ORDER.index(m.group(2)) > ORDER.index(layer):
                    bad.append(f"{f}:{n}: layer '{layer}' includes higher layer '{m.group(2)}'")
                if m and m.group(1) in PRIVATE and m.group(2) != layer:
                    bad.append(f"{f}:{n}: layer '{layer}' includes '{m.group(1)}', private to layer '{m.group(2)}'")
    return bad, f"checked layers under {root}"


def check_apps(root, apps=APPS):
    bad, files = [], 0
    for app in apps:
        folder = root / app
        if not folder.is_dir():
            bad.append(f"{folder}: missing")
            continue
        for f in sorted(folder.rglob("*")):
            if f.suffix not in SOURCES:
                continue
            files += 1
            for n, line in enumerate(f.read_text(encoding="utf-8").splitlines(), 1):
                m = quoted.match(line)
                if m and m.group(1) not in PUBLIC and not (f.parent / m.group(1)).is_file():
                    bad.append(
                        f'{f}:{n}: includes "{m.group(1)}", which is neither silk/silk.h, '
                        f"silk/silk.hpp nor a file of {app}"
                    )
    return bad, f"checked {files} app sources under {root} (public API only)"


def selftest():
    with tempfile.TemporaryDirectory() as tmp:
        app = pathlib.Path(tmp) / "silktok"
        app.mkdir()
        (app / "local.h").write_text("#pragma once\n")
        (app / "main.cpp").write_text('#include "silk/silk.hpp"\n#include "local.h"\n')
        clean, _ = check_apps(pathlib.Path(tmp), ["silktok"])
        (app / "bad.cpp").write_text('#include <vector>\n#include "tokenizer/tokenizer.h"\n')
        dirty, _ = check_apps(pathlib.Path(tmp), ["silktok"])
    ok = not clean and len(dirty) == 1 and "tokenizer/tokenizer.h" in dirty[0]
    print(f"selftest: clean app -> {len(clean)} finding(s); app including tokenizer/tokenizer.h -> {dirty}")
    return [] if ok else ["the apps check does not catch an engine-internal include"], "apps check selftest"


MAX_FILES_PER_FOLDER = 40


def check_folders(root):
    bad, folders = [], 0
    for d in sorted([root] + [p for p in root.rglob("*") if p.is_dir()]):
        folders += 1
        n = sum(1 for f in d.iterdir() if f.is_file() and f.suffix in SOURCES)
        if n > MAX_FILES_PER_FOLDER:
            bad.append(f"{d}: {n} source files directly inside (at most {MAX_FILES_PER_FOLDER})")
    return bad, f"checked {folders} folders under {root}"


def private_selftest():
    with tempfile.TemporaryDirectory() as tmp:
        root = pathlib.Path(tmp)
        for layer in ORDER:
            (root / layer).mkdir()
        (root / "tokenizer" / "processed_mesh.h").write_text("#pragma once\n")
        (root / "tokenizer" / "stage.cpp").write_text('#include "tokenizer/processed_mesh.h"\n')
        clean, _ = check_engine(root)
        (root / "decoder" / "bad.cpp").write_text('#include "tokenizer/processed_mesh.h"\n')
        dirty, _ = check_engine(root)
    ok = not clean and len(dirty) == 1 and "private to layer 'tokenizer'" in dirty[0]
    print(f"selftest: tokenizer including its own header -> {len(clean)} finding(s); decoder including it -> {dirty}")
    return [] if ok else ["the engine check does not catch a layer-private include"], "private headers selftest"


STAGE_LINE = re.compile(r"^Stage order[^`\n]*`([^`]+)`", re.M)


def read_stage_order(readme):
    """{stage: rank} from the README's "Stage order: `a -> b | c`" line; None when it has none."""
    m = STAGE_LINE.search(readme.read_text(encoding="utf-8")) if readme.is_file() else None
    if not m:
        return None
    return {name.strip(): rank for rank, peers in enumerate(m.group(1).split("->")) for name in peers.split("|")}


def stage_findings(deps, order, layer):
    """Back includes among the stages of one layer. deps: {file: [(line, included file)]}, paths
    relative to the layer ("packing/token_reader.cpp", "tokenizer.h"); order: {stage: rank}."""

    def stage(f):
        return f.split("/")[0] if "/" in f else None

    reach_memo = {}

    def reach(f, seen):  # the stages a top-level file reaches through its includes
        if f in reach_memo:
            return reach_memo[f]
        out = set()
        for _, g in deps.get(f, []):
            if stage(g):
                out.add(stage(g))
            if g not in seen:
                out |= reach(g, seen | {g})
        reach_memo[f] = out
        return out

    chain = " -> ".join(" | ".join(k for k, r in order.items() if r == i) for i in sorted(set(order.values())))
    bad = [
        f"{layer}/{s}: sub-folder not in {layer}'s stage order ({chain})"
        for s in sorted({stage(f) for f in deps if stage(f)} - set(order))
    ]
    for f in sorted(deps):
        a = stage(f)
        if a is None or a not in order:
            continue
        for n, g in deps[f]:
            b = stage(g)
            reached = {b} if b else reach(g, {g})
            for c in sorted(x for x in reached if x != a and x in order and order[x] >= order[a]):
                how = "" if b else f", which reaches stage '{c}'"
                rel = "a peer" if order[c] == order[a] else "after it"
                bad.append(
                    f"{layer}/{f}:{n}: stage '{a}' includes '{g}'{how}: '{c}' comes {rel} in "
                    f"{layer}'s stage order ({chain})"
                )
    return bad


def cpp_deps(folder, layer):
    """{file: [(line, included file)]} for a layer's includes of its own files ("layer/...")."""
    inc = re.compile(r'^\s*#\s*include\s*"' + re.escape(layer) + r'/([^"]+)"')
    deps = {}
    for f in sorted(folder.rglob("*")):
        if f.suffix in SOURCES:
            lines = f.read_text(encoding="utf-8").splitlines()
            deps[f.relative_to(folder).as_posix()] = [
                (n, m.group(1)) for n, l in enumerate(lines, 1) if (m := inc.match(l))
            ]
    return deps


def check_stages(root):
    bad, layers = [], []
    for layer in ORDER:
        folder = root / layer
        if not folder.is_dir() or not any(p.is_dir() for p in folder.iterdir()):
            continue
        order = read_stage_order(folder / "README.md")
        if order is None:
            bad.append(f"{folder / 'README.md'}: no 'Stage order: `a -> b`' line for the sub-folders of {layer}/")
            continue
        layers.append(
            f"{layer}: "
            + " -> ".join(" | ".join(k for k, r in order.items() if r == i) for i in sorted(set(order.values())))
        )
        bad += stage_findings(cpp_deps(folder, layer), order, layer)
    print("\n".join(layers))
    return bad, f"checked the stage order of {len(layers)} layers under {root}"


def python_deps(pkg):
    """{module file: [(line, imported module file)]} for a package's imports of itself (relative,
    absolute, and imports inside functions), paths relative to the package."""
    files = {f.relative_to(pkg).as_posix() for f in pkg.rglob("*.py")}

    def resolve(parts):  # a module path inside the package -> its file, or None
        for cand in ("/".join(parts) + ".py", "/".join(parts + ["__init__"]) + ".py"):
            if cand in files:
                return cand
        return None

    deps = {}
    for rel in sorted(files):
        here = rel.split("/")[:-1]
        out = []
        for node in ast.walk(ast.parse((pkg / rel).read_text(encoding="utf-8"))):
            targets = []
            if isinstance(node, ast.ImportFrom):
                if node.level:
                    base = here[: len(here) - (node.level - 1)] if node.level > 1 else here
                elif node.module and node.module.split(".")[0] == pkg.name:
                    base = []
                    node_module = node.module.split(".")[1:]
                    targets = [base + node_module + [a.name] for a in node.names] + [base + node_module]
                else:
                    continue
                if node.level:
                    mod = base + (node.module.split(".") if node.module else [])
                    targets = [mod + [a.name] for a in node.names] + [mod]
            elif isinstance(node, ast.Import):
                targets = [a.name.split(".")[1:] for a in node.names if a.name.split(".")[0] == pkg.name]
            for t in targets:  # "from .x import y": module x.y if it is one, else module x
                hit = resolve(t) if t else None
                if hit:
                    out.append((node.lineno, hit))
                    break
        deps[rel] = [(n, g) for n, g in out if g != rel]
    return deps


def check_python_stages(pkg, readme):
    order = read_stage_order(readme)
    if order is None:
        return [f"{readme}: no 'Stage order: `a -> b`' line for the sub-packages of {pkg.name}"], "python stages"
    print(
        f"{pkg.name}: "
        + " -> ".join(" | ".join(k for k, r in order.items() if r == i) for i in sorted(set(order.values())))
    )
    return stage_findings(python_deps(pkg), order, pkg.name), f"checked the stage order of {pkg}"


def stages_selftest():
    with tempfile.TemporaryDirectory() as tmp:
        layer = pathlib.Path(tmp) / "tokenizer"
        for d in ("cleanup", "packing"):
            (layer / d).mkdir(parents=True)
        (layer / "README.md").write_text("Stage order: `cleanup -> packing`\n")
        (layer / "cleanup" / "quantize.h").write_text("#pragma once\n")
        (layer / "shared.h").write_text('#include "tokenizer/packing/stream.h"\n')
        (layer / "packing" / "stream.h").write_text('#include "tokenizer/cleanup/quantize.h"\n')
        clean, _ = check_stages(pathlib.Path(tmp))
        (layer / "cleanup" / "quantize.cpp").write_text('#include "tokenizer/packing/stream.h"\n')
        (layer / "cleanup" / "face.cpp").write_text('#include "tokenizer/shared.h"\n')
        dirty, _ = check_stages(pathlib.Path(tmp))
        pkg = pathlib.Path(tmp) / "pkg"
        for d in ("models", "onnx"):
            (pkg / d).mkdir(parents=True)
            (pkg / d / "__init__.py").write_text("")
        (pkg / "__init__.py").write_text("")
        (pkg / "onnx" / "export.py").write_text("from ..models import net\n")
        (pkg / "models" / "net.py").write_text("def f():\n    from pkg.onnx.export import g\n")
        (pkg / "README.md").write_text("Stage order: `models -> onnx`\n")
        py, _ = check_python_stages(pkg, pkg / "README.md")
    want = [
        "cleanup/quantize.cpp:1: stage 'cleanup' includes 'packing/stream.h'",
        "cleanup/face.cpp:1: stage 'cleanup' includes 'shared.h', which reaches stage 'packing'",
        "models/net.py:2: stage 'models' includes 'onnx/export.py'",
    ]
    found = dirty + py
    ok = not clean and len(found) == 3 and all(any(w in b for b in found) for w in want)
    print(f"selftest: ordered layer -> {len(clean)} finding(s); planted back includes -> {found}")
    return [] if ok else ["the stage check does not catch a back include"], "stage order selftest"


def main():
    args = sys.argv[1:]
    if args[:1] == ["--apps"]:
        bad, what = check_apps(pathlib.Path(args[1] if len(args) > 1 else "apps"))
    elif args[:1] == ["--folders"]:
        bad, what = check_folders(pathlib.Path(args[1] if len(args) > 1 else "engine"))
    elif args[:1] == ["--apps-selftest"]:
        bad, what = selftest()
    elif args[:1] == ["--private-selftest"]:
        bad, what = private_selftest()
    elif args[:1] == ["--stages"]:
        bad, what = check_stages(pathlib.Path(args[1] if len(args) > 1 else "engine"))
    elif args[:1] == ["--python-stages"] and len(args) == 3:
        bad, what = check_python_stages(pathlib.Path(args[1]), pathlib.Path(args[2]))
    elif args[:1] == ["--stages-selftest"]:
        bad, what = stages_selftest()
    else:
        bad, what = check_engine(pathlib.Path(args[0] if args else "engine"))
    for b in bad:
        print(b)
    print(f"{what}: {len(bad)} violation(s)")
    sys.exit(1 if bad else 0)


if __name__ == "__main__":
    main()
