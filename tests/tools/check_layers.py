#!/usr/bin/env python3
"""Enforces the engine's layering: a lower layer never includes a higher one.
Order: core -> io -> mesh -> tokenizer -> decoder -> runtime -> capi (the C API sees all)."""
import pathlib, re, sys

ORDER = ["core", "io", "mesh", "tokenizer", "decoder", "runtime", "capi"]
root = pathlib.Path(sys.argv[1] if len(sys.argv) > 1 else "engine")
inc = re.compile(r'^\s*#\s*include\s*"([a-z_]+)/')
bad = []
for layer in ORDER:
    for f in sorted((root / layer).rglob("*")):
        if f.suffix not in (".h", ".hpp", ".cpp", ".cc"):
            continue
        for n, line in enumerate(f.read_text(encoding="utf-8").splitlines(), 1):
            m = inc.match(line)
            if m and m.group(1) in ORDER and ORDER.index(m.group(1)) > ORDER.index(layer):
                bad.append(f"{f}:{n}: layer '{layer}' includes higher layer '{m.group(1)}'")
for b in bad:
    print(b)
print(f"checked layers under {root}: {len(bad)} violation(s)")
sys.exit(1 if bad else 0)
