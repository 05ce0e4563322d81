#!/usr/bin/env python3
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
Headers in PRIVATE belong to their layer alone (docs/mesh_types.md): no other layer includes them.
"""
import pathlib, re, sys, tempfile

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
                    bad.append(f"{f}:{n}: includes \"{m.group(1)}\", which is neither silk/silk.h, "
                               f"silk/silk.hpp nor a file of {app}")
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
    else:
        bad, what = check_engine(pathlib.Path(args[0] if args else "engine"))
    for b in bad:
        print(b)
    print(f"{what}: {len(bad)} violation(s)")
    sys.exit(1 if bad else 0)


if __name__ == "__main__":
    main()
