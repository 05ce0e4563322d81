#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""The silk_mesh binding's ctypes declarations (bindings/python/silk_mesh/_capi.py) against the C
compiler's view of silk.h: for every ctypes Structure, a generated C file prints sizeof of the
struct (silk_<snake_case of the class name>) and offsetof and sizeof of each field, named as in
the ctypes _fields_ (a renamed field does not compile, a reordered or retyped one moves); the
figures must equal ctypes'. Then every function the binding declares must exist in libsilk.

  check_capi_layout.py --cc CC --include DIR --library LIBSILK [--selftest]
  --selftest: also checks that a copy of silk_encode_params with two fields swapped fails."""

import argparse
import ctypes
import pathlib
import re
import subprocess
import sys
import tempfile

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[2] / "bindings" / "python"))
from silk_mesh import _capi  # noqa: E402  (declarations only: loads no library)


def structures() -> dict:
    """{C struct name: ctypes class} for every Structure _capi declares."""
    out = {}
    for name, obj in vars(_capi).items():
        # Concrete structs only (an abstract base such as _Sized declares no _fields_).
        if isinstance(obj, type) and issubclass(obj, ctypes.Structure) and "_fields_" in vars(obj):
            out["silk_" + re.sub(r"(?<!^)(?=[A-Z])", "_", name).lower()] = obj
    return out


def c_program(structs: dict) -> str:
    lines = ["#include <stddef.h>", "#include <stdio.h>", '#include "silk/silk.h"', "int main(void) {"]
    for cname, cls in structs.items():
        lines.append(f'  printf("{cname} . %zu %zu\\n", (size_t)0, sizeof({cname}));')
        for field, _ in cls._fields_:
            lines.append(
                f'  printf("{cname} {field} %zu %zu\\n", offsetof({cname}, {field}), sizeof((({cname}*)0)->{field}));'
            )
    return "\n".join(lines + ["  return 0;", "}", ""])


def c_layout(cc: str, include: str, structs: dict) -> dict:
    """{(struct, field or "."): (offset, size)} as the C compiler lays silk.h out."""
    with tempfile.TemporaryDirectory() as tmp:
        src, exe = pathlib.Path(tmp) / "layout.c", pathlib.Path(tmp) / "layout"
        src.write_text(c_program(structs))
        r = subprocess.run([cc, "-std=c99", "-I", include, str(src), "-o", str(exe)], capture_output=True, text=True)
        if r.returncode != 0:
            raise SystemExit(f"FAIL the C compiler rejects the binding's field names:\n{r.stderr[-3000:]}")
        out = subprocess.run([str(exe)], capture_output=True, text=True, check=True).stdout
    layout = {}
    for line in out.splitlines():
        struct, field, off, size = line.split()
        layout[(struct, field)] = (int(off), int(size))
    return layout


def compare(structs: dict, layout: dict) -> list[str]:
    bad = []
    for cname, cls in structs.items():
        if layout[(cname, ".")][1] != ctypes.sizeof(cls):
            bad.append(f"{cname}: sizeof {layout[(cname, '.')][1]} in C, {ctypes.sizeof(cls)} in ctypes {cls.__name__}")
        for field, _ in cls._fields_:
            desc = getattr(cls, field)
            want = layout[(cname, field)]
            if (desc.offset, desc.size) != want:
                bad.append(f"{cname}.{field}: offset/size {want} in C, ({desc.offset}, {desc.size}) in ctypes")
    return bad


def missing_functions(library: str) -> list[str]:
    lib = ctypes.CDLL(library)
    return [
        f"{name}: declared in _capi.SIGNATURES, not exported by {library}"
        for name in _capi.SIGNATURES
        if not hasattr(lib, name)
    ]


def swapped_copy(cls):
    """cls with its first two fields swapped (the selftest's deliberate break)."""
    fields = list(cls._fields_)
    fields[0], fields[1] = fields[1], fields[0]
    return type(cls.__name__, (ctypes.Structure,), {"_fields_": fields})


def main() -> int:
    ap = argparse.ArgumentParser()
    ap.add_argument("--cc", required=True)
    ap.add_argument("--include", required=True)
    ap.add_argument("--library", required=True)
    ap.add_argument("--selftest", action="store_true")
    a = ap.parse_args()
    structs = structures()
    layout = c_layout(a.cc, a.include, structs)
    bad = compare(structs, layout) + missing_functions(a.library)
    fields = sum(len(c._fields_) for c in structs.values())
    print(f"{len(structs)} structs ({fields} fields) and {len(_capi.SIGNATURES)} functions checked")
    if a.selftest:
        broken = compare({"silk_encode_params": swapped_copy(_capi.EncodeParams)}, layout)
        print(f"selftest: silk_encode_params with its first two fields swapped -> {len(broken)} finding(s)")
        if not broken:
            bad.append("selftest: a swapped field pair went unnoticed")
    for line in bad:
        print("FAIL", line)
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
