#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""A release-size stand-in for the released checkpoint: every key of the official release
(../shared/official-model/release_keys.tsv: 804 tensors, the release's shapes) as F32 random values
in one safetensors file of the release's size (2.89 GB of data), written tensor by tensor (a few
hundred MB of memory). What `silk-export import-official` is timed on when the real weights cannot be
downloaded (README, "Run the released Mesh Silksong model"):

    python3 bench/release_checkpoint.py /tmp/release/model.safetensors [--shared ../shared]
    /usr/bin/time -v silk-export import-official /tmp/release/model.safetensors -o /tmp/release/silksong
"""

import argparse
import json
import os
import struct
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "export"))  # this checkout's silk_export
from silk_export.paths import shared_dir  # noqa: E402  (the one shared-folder rule)


def layout(shared: Path) -> list[tuple[str, list[int]]]:
    rows = (shared / "official-model" / "release_keys.tsv").read_text().splitlines()[1:]
    return [(r.split("\t")[0], [int(d) for d in r.split("\t")[1].split("x")]) for r in rows]


def write(path: Path, keys, seed: int = 0) -> int:
    header, offset = {"__metadata__": {"format": "pt"}}, 0
    for name, shape in keys:
        n = 4 * int(np.prod(shape))
        header[name] = {"dtype": "F32", "shape": shape, "data_offsets": [offset, offset + n]}
        offset += n
    head = json.dumps(header).encode()
    head += b" " * (-len(head) % 8)
    rng = np.random.default_rng(seed)
    path.parent.mkdir(parents=True, exist_ok=True)
    tmp = path.with_name(path.name + ".part")
    with open(tmp, "wb") as f:
        f.write(struct.pack("<Q", len(head)) + head)
        for _name, shape in keys:  # LayerNorm-like scales near 1 would not matter: any finite values import
            f.write((rng.standard_normal(shape, dtype=np.float32) * 0.02).tobytes())
    os.replace(tmp, path)
    return offset


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("out", type=Path)
    ap.add_argument(
        "--shared", type=Path, help="the shared material folder (default: $SILK_SHARED_DIR, else ../shared)"
    )
    a = ap.parse_args()
    a.shared = a.shared or shared_dir(required=True)
    keys = layout(a.shared)
    data = write(a.out, keys)
    print(f"{a.out}: {len(keys)} F32 tensors, {data:,} bytes of data, {a.out.stat().st_size:,} bytes")


if __name__ == "__main__":
    main()
