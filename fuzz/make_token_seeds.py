#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Writes seed inputs for the token fuzzers from official golden token files, in each
fuzzer's byte encoding: token_decoder_fuzzer (0xF0 + little-endian int32 per id) and
grammar_fuzzer (one flag byte, then a little-endian uint16 per id).
Usage: python3 fuzz/make_token_seeds.py [SHARED_DIR]   (default: the shared folder, silk_export.paths)"""

import pathlib
import struct
import sys

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1] / "export"))  # this checkout's silk_export
from silk_export.paths import shared_dir  # noqa: E402  (the one shared-folder rule)

NAMES = ["tetrahedron", "cube", "grid", "two_components", "nonmanifold_book", "torus_12x8", "open_tube"]


def main():
    repo = pathlib.Path(__file__).resolve().parent.parent
    shared = pathlib.Path(sys.argv[1]) if len(sys.argv) > 1 else shared_dir(required=True)
    dec = repo / "fuzz" / "corpus" / "token_decoder_fuzzer"
    gram = repo / "fuzz" / "corpus" / "grammar_fuzzer"
    dec.mkdir(parents=True, exist_ok=True)
    gram.mkdir(parents=True, exist_ok=True)
    for name in NAMES:
        ids = [int(x) for x in (shared / "spec" / "golden" / f"{name}.tokens.txt").read_text().split()]
        (dec / f"{name}.bin").write_bytes(b"".join(b"\xf0" + struct.pack("<i", i) for i in ids))
        (gram / f"{name}.bin").write_bytes(bytes([2]) + b"".join(struct.pack("<H", i) for i in ids))
    print(f"wrote {len(NAMES)} seeds each to {dec} and {gram}")


if __name__ == "__main__":
    main()
