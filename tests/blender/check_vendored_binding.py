#!/usr/bin/env python3
"""The add-on zip carries the Python binding unchanged: every file of bindings/python/silk_mesh
(*.py and README.md) is in the zip under silk_blender/silk_mesh/ byte for byte, and the zip holds
no other Python file there (lib/ and model/ are the bundled library and model).

  check_vendored_binding.py ZIP SOURCE_DIR   exit 1 naming each difference"""
import pathlib
import sys
import zipfile

PREFIX = "silk_blender/silk_mesh/"


def differences(zip_path: pathlib.Path, source: pathlib.Path) -> list[str]:
    src = {p.name: p.read_bytes() for p in sorted(source.iterdir()) if p.suffix == ".py" or p.name == "README.md"}
    with zipfile.ZipFile(zip_path) as z:
        vendored = {n[len(PREFIX):]: z.read(n) for n in z.namelist()
                    if n.startswith(PREFIX) and "/" not in n[len(PREFIX):] and n[len(PREFIX):]}
    bad = [f"{PREFIX}{n}: missing from the zip" for n in src if n not in vendored]
    bad += [f"{PREFIX}{n}: differs from {source / n}" for n in src if n in vendored and vendored[n] != src[n]]
    bad += [f"{PREFIX}{n}: not in {source}" for n in vendored if n not in src]
    return bad


def main() -> int:
    zip_path, source = pathlib.Path(sys.argv[1]), pathlib.Path(sys.argv[2]) / "bindings" / "python" / "silk_mesh"
    bad = differences(zip_path, source)
    for line in bad:
        print("FAIL", line)
    n = sum(1 for p in source.iterdir() if p.suffix == ".py" or p.name == "README.md")
    print(f"{zip_path}: {n} files of {source} vendored, {len(bad)} difference(s)")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
