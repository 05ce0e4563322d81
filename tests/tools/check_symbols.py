#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""libsilk.so exports exactly the C API: the dynamic symbols of the built library, the functions
silk.h declares and the committed list engine/libsilk.symbols are the same set, and every one is
silk_* (docs/c_api.md "Exported symbols"). onnxruntime's custom-op library entry lives in
libsilk_ops, which exports it alone (--plugin).

  check_symbols.py LIB LIST HEADER           compare; fails naming added / missing / non-silk_ symbols
  check_symbols.py --plugin OPS_LIB          libsilk_ops exports exactly PLUGIN_ENTRIES
  check_symbols.py --write LIB LIST HEADER   regenerate LIST from LIB (after an intended API change;
                                             the header must agree with it)
  check_symbols.py --selftest                the comparison fails on a known bad set (the check can fail)
"""

import re
import subprocess
import sys

DECL = re.compile(r"^SILK_API\s+[^;(]*?\b(silk_\w+)\s*\(", re.M)
# libsilk_ops' entries, names other programs look up: onnxruntime's for a custom-op library
# (engine/kernels/ops_library_entry.cpp).
PLUGIN_ENTRIES = {"RegisterCustomOps"}


def exported(lib):
    """Defined dynamic symbols of LIB (nm -D --defined-only)."""
    out = subprocess.run(["nm", "-D", "--defined-only", lib], check=True, capture_output=True, text=True).stdout
    names = set()
    for line in out.splitlines():
        parts = line.split()
        if len(parts) >= 3 and parts[1] != "A":  # "A": a version node (SILK_1.0), not a symbol
            names.add(parts[2].split("@")[0])
    return names


def declared(header):
    with open(header, encoding="utf-8") as f:
        return set(DECL.findall(f.read()))


def read_list(path):
    with open(path, encoding="utf-8") as f:
        return {l.strip() for l in f if l.strip() and not l.startswith("#")}


def problems(lib_syms, listed, header_syms):
    """Every difference, one line each (empty: all agree)."""
    out = [f"not a silk_ symbol: {s}" for s in sorted(lib_syms) if not s.startswith("silk_")]
    out += [f"exported but not in the list (added): {s}" for s in sorted(lib_syms - listed)]
    out += [f"in the list but not exported (missing): {s}" for s in sorted(listed - lib_syms)]
    out += [f"exported but not declared in silk.h: {s}" for s in sorted(lib_syms - header_syms)]
    out += [f"declared in silk.h but not exported: {s}" for s in sorted(header_syms - lib_syms)]
    return out


HOW = (
    "python3 tests/tools/check_symbols.py --write build/engine/libsilk.so engine/libsilk.symbols "
    "engine/include/silk/silk.h"
)


def plugin_problems(lib_syms):
    """libsilk_ops' differences from PLUGIN_ENTRIES, one line each."""
    out = [f"libsilk_ops exports more than its entry: {s}" for s in sorted(lib_syms - PLUGIN_ENTRIES)]
    return out + [f"libsilk_ops does not export: {s}" for s in sorted(PLUGIN_ENTRIES - lib_syms)]


def selftest():
    bad = problems({"silk_a", "silk_new", "helper"}, {"silk_a", "silk_gone"}, {"silk_a", "silk_new"})
    bad += problems({"silk_a", "RegisterCustomOps"}, {"silk_a", "RegisterCustomOps"}, {"silk_a"})  # libsilk
    bad += plugin_problems({"silk_a"})
    want = [
        "not a silk_ symbol: helper",
        "added): helper",
        "added): silk_new",
        "missing): silk_gone",
        "not declared in silk.h: helper",
        "not a silk_ symbol: RegisterCustomOps",
        "more than its entry: silk_a",
        "does not export: RegisterCustomOps",
    ]
    missing = [w for w in want if not any(w in b for b in bad)]
    ok = {"silk_a"}
    if missing or problems(ok, ok, ok) or plugin_problems(PLUGIN_ENTRIES):
        print("selftest failed:", missing or "a matching set reported problems")
        return 1
    print(
        "selftest ok: the comparison reports added, missing and non-silk_ symbols (RegisterCustomOps "
        "on libsilk too), and a libsilk_ops exporting more or less than its entry"
    )
    return 0


def main(argv):
    if argv[1:] == ["--selftest"]:
        return selftest()
    if argv[1:2] == ["--plugin"] and len(argv) == 3:
        bad = plugin_problems(exported(argv[2]))
        print("\n".join(bad) if bad else f"{argv[2]} exports {', '.join(sorted(PLUGIN_ENTRIES))} alone")
        return 1 if bad else 0
    write = argv[1:2] == ["--write"]
    args = argv[2:] if write else argv[1:]
    if len(args) != 3:
        print(__doc__)
        return 2
    lib, listed_path, header = args
    lib_syms, header_syms = exported(lib), declared(header)
    if write:
        bad = problems(lib_syms, lib_syms, header_syms)
        if bad:
            print("\n".join(bad))
            return 1
        with open(listed_path, "w", encoding="utf-8") as f:
            f.write("# The dynamic symbols of libsilk.so: the C API of silk.h (docs/c_api.md). Regenerate with\n")
            f.write(f"# {HOW}\n")
            f.write("".join(s + "\n" for s in sorted(lib_syms)))
        print(f"wrote {len(lib_syms)} symbols to {listed_path}")
        return 0
    bad = problems(lib_syms, read_list(listed_path), header_syms)
    if bad:
        print("\n".join(bad))
        print(f"after an intended API change, regenerate the list: {HOW}")
        return 1
    print(f"{len(lib_syms)} exported symbols: all silk_*, as listed and declared")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
