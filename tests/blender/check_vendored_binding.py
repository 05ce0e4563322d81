#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""The add-on zip carries the Python binding unchanged: every file of bindings/python/silk_mesh
(*.py and README.md) is in the zip under silk_blender/silk_mesh/ byte for byte, and the zip holds
no other Python file there (lib/ and model/ are the bundled library and model). And every bundled
Linux library finds the others it needs in lib/ itself (RUNPATH $ORIGIN), not only where the
machine happens to have a system copy (Debian's libstb0 for libtinygltf, say).

  check_vendored_binding.py ZIP SOURCE_DIR   exit 1 naming each difference"""

import pathlib
import subprocess
import sys
import tempfile
import zipfile

PREFIX = "silk_blender/silk_mesh/"


def differences(zip_path: pathlib.Path, source: pathlib.Path) -> list[str]:
    src = {p.name: p.read_bytes() for p in sorted(source.iterdir()) if p.suffix == ".py" or p.name == "README.md"}
    with zipfile.ZipFile(zip_path) as z:
        vendored = {
            n[len(PREFIX) :]: z.read(n)
            for n in z.namelist()
            if n.startswith(PREFIX) and "/" not in n[len(PREFIX) :] and n[len(PREFIX) :]
        }
    bad = [f"{PREFIX}{n}: missing from the zip" for n in src if n not in vendored]
    bad += [f"{PREFIX}{n}: differs from {source / n}" for n in src if n in vendored and vendored[n] != src[n]]
    bad += [f"{PREFIX}{n}: not in {source}" for n in vendored if n not in src and n != "LICENSE"]  # the repository's
    return bad


def unresolved_bundled(zip_path: pathlib.Path) -> list[str]:
    """Each ELF in lib/ that needs another library of lib/ must search its own folder ($ORIGIN)."""
    bad = []
    with zipfile.ZipFile(zip_path) as z, tempfile.TemporaryDirectory() as tmp:
        libs = [n for n in z.namelist() if n.startswith(PREFIX + "lib/") and ".so" in n.rsplit("/", 1)[-1]]
        names = {n.rsplit("/", 1)[-1] for n in libs}
        for n in libs:
            path = pathlib.Path(tmp) / n.rsplit("/", 1)[-1]
            path.write_bytes(z.read(n))
            dyn = subprocess.run(["readelf", "-d", str(path)], capture_output=True, text=True, check=True).stdout
            needed = [line.split("[", 1)[1].split("]", 1)[0] for line in dyn.splitlines() if "(NEEDED)" in line]
            paths = [
                line.split("[", 1)[1].split("]", 1)[0]
                for line in dyn.splitlines()
                if "(RUNPATH)" in line or "(RPATH)" in line
            ]
            origin = any("$ORIGIN" == p.rstrip("/") for entry in paths for p in entry.split(":"))
            for dep in needed:
                if dep in names and not origin:
                    bad.append(f"{n}: needs {dep} (bundled beside it) but has no RUNPATH $ORIGIN to find it")
    return bad


def main() -> int:
    zip_path, source = pathlib.Path(sys.argv[1]), pathlib.Path(sys.argv[2]) / "bindings" / "python" / "silk_mesh"
    bad = differences(zip_path, source) + unresolved_bundled(zip_path)
    for line in bad:
        print("FAIL", line)
    n = sum(1 for p in source.iterdir() if p.suffix == ".py" or p.name == "README.md")
    print(f"{zip_path}: {n} files of {source} vendored, {len(bad)} difference(s)")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
