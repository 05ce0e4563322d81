# SPDX-License-Identifier: MIT
"""`silk-export dataset`: one pass over a mesh collection through libsilk. A build job encodes
one shard of the sorted file list (`--shard I/N`: files I, I+N, I+2N, ...) into a compact
cache (shard_store.py); merging the N shards writes dataset.json (the shard list), index.jsonl
(one row per mesh in file order: key, file, split, faces, token count, refusal, shard, slot),
refused.tsv and summary.json. Training streams from the shards (sharded_dataset.py)."""

from __future__ import annotations

import json
import time
from collections import Counter
from pathlib import Path

import numpy as np
import silk_mesh
from tqdm import tqdm

from ..json_io import jsonl_line, write_json
from ..paths import shared_dir
from .mesh_files import list_meshes
from .shard_store import Shard, ShardWriter, shard_name, write_refused
from .splits import TRAIN, DevExclusion, assign_split, load_dev_exclusion, shape_key

DATASET_FORMAT = "silk-dataset/1"


def dev_exclusion(dev_dir: Path | None, pmd_root: Path | None = None) -> DevExclusion:
    """Dev corpus paths and shape keys (from its OBJ files and, when present, the original PMDs)."""
    if not dev_dir:
        shared = shared_dir()
        if shared is None:
            raise SystemExit(
                "silk-export dataset: no dev corpus to keep out of training: pass --dev-dir DIR, set "
                "SILK_SHARED_DIR (its corpus/dev is used; from a checkout, ../shared beside it), or --all-train"
            )
        dev_dir = shared / "corpus" / "dev"
    dev_dir = Path(dev_dir)
    ex = load_dev_exclusion(dev_dir, silk_mesh.load_arrays)
    if pmd_root is not None:
        for zp in sorted(ex.zip_paths):
            p = Path(pmd_root) / zp
            if p.is_file():
                v, f = silk_mesh.load_arrays(p)
                ex.shape_keys.add(shape_key(v, f.shape[0]))
    return ex


def encode_one(key: str, path: Path, root: Path, dev: DevExclusion | None):
    """(index row, tokens, positions, triangles); arrays are None for a refused mesh.
    dev=None: no split assignment (every mesh is training data)."""
    row = {"key": key, "file": path.relative_to(root).as_posix()}
    arrays = (None, None, None)
    try:
        v, f = silk_mesh.load_arrays(path)
        row.update(vertices=int(v.shape[0]), faces=int(f.shape[0]))
        row["split"] = TRAIN if dev is None else assign_split(key, shape_key(v, f.shape[0]), dev)
        ids, stats = silk_mesh.encode((v, f), return_stats=True)
        tokens = np.asarray(ids, dtype=np.int32)
        row.update(
            tokens=int(tokens.size),
            processed_faces=int(stats["processed_faces"]),
            layers=int(stats["layers"]),
            max_layer_size=int(stats["max_layer_size"]),
            refused=None,
        )
        arrays = (tokens, v, f)
    except silk_mesh.SilkError as e:
        refused = e.reason if e.status == silk_mesh.SILK_ERR_REFUSED else f"error:{e.name}"
        row.update(tokens=None, refused=refused, detail=e.message)
    if "split" not in row:
        row["split"] = TRAIN if dev is None else assign_split(key, "", dev)
    return (row, *arrays)


def build_shard(
    root: Path,
    out_dir: Path,
    shard: tuple[int, int] = (0, 1),
    dev_dir: Path | None = None,
    limit: int | None = None,
    all_train: bool = False,
    progress: bool = True,
) -> Path:
    """Encodes files shard[0], shard[0] + N, ... of the sorted listing into out_dir/shard-I-of-N."""
    root, (i, n) = Path(root), shard
    files = list_meshes(root)
    if limit:
        files = files[:limit]
    dev = None if all_train else dev_exclusion(dev_dir, pmd_root=root if (root / "art" / "meshes").is_dir() else None)
    writer = ShardWriter(Path(out_dir), i, n)
    t0 = time.time()
    mine = list(range(i, len(files), n))
    for order in tqdm(mine, desc=f"shard {i}/{n}", unit="mesh", disable=not progress):
        key, path = files[order]
        row, tokens, v, f = encode_one(key, path, root, dev)
        writer.add({**row, "order": order}, tokens, v, f)
    return writer.close(
        {"root": str(root), "files_total": len(files), "all_train": all_train, "seconds": round(time.time() - t0, 1)}
    )


def merge_shards(out_dir: Path) -> dict:
    """Checks that every shard of one build is there and writes the dataset's index files."""
    out_dir = Path(out_dir)
    found = sorted(p for p in out_dir.glob("shard-*-of-*") if p.is_dir() and not p.name.endswith(".tmp"))
    if not found:
        raise ValueError(f"{out_dir}: no finished shard-I-of-N folders to merge")
    n = Shard(found[0]).info["of"]
    names = [shard_name(i, n) for i in range(n)]
    missing = [s for s in names if not (out_dir / s).is_dir()]
    if missing:
        raise ValueError(f"{out_dir}: shards missing: {', '.join(missing)}")
    rows = []
    for s, name in enumerate(names):
        rows += [{**r, "shard": s} for r in Shard(out_dir / name).rows()]
    rows.sort(key=lambda r: r["order"])
    write_rows(out_dir / "index.jsonl", rows)
    with open(out_dir / "refused.tsv", "w") as fh:
        write_refused(fh, [r for r in rows if r["refused"]])
    info = Shard(out_dir / names[0]).info
    summary = {
        "root": info["root"],
        "meshes": len(rows),
        "shards": n,
        "splits": dict(Counter(r["split"] for r in rows)),
        "encodable_by_split": dict(Counter(r["split"] for r in rows if r["refused"] is None)),
        "refusals": dict(Counter(r["refused"] for r in rows if r["refused"])),
    }
    write_json(out_dir / "summary.json", summary, "null")
    write_json(
        out_dir / "dataset.json",
        {"format": DATASET_FORMAT, "shards": names, "meshes": len(rows), "all_train": info["all_train"]},
    )
    return summary


def build_index(
    root: Path, out_dir: Path, dev_dir: Path | None = None, limit: int | None = None, all_train: bool = False
) -> dict:
    """Unsharded build: one shard, then the merge (index.jsonl, summary.json, dataset.json)."""
    t0 = time.time()
    for old in Path(out_dir).glob("shard-*-of-*"):  # a previous build with another N
        if old.is_dir() and old.name != shard_name(0, 1):
            raise ValueError(f"{out_dir} holds {old.name}; use an empty folder")
    build_shard(root, out_dir, (0, 1), dev_dir, limit, all_train)
    return {**merge_shards(out_dir), "seconds": round(time.time() - t0, 1)}


def write_rows(path: Path, rows: list[dict]) -> None:
    tmp = Path(path).with_suffix(".jsonl.tmp")
    with open(tmp, "w") as fh:
        for r in rows:
            fh.write(jsonl_line(r, what=f"{path}: row {r.get('key')}"))
    tmp.replace(path)


def read_index(path: Path) -> list[dict]:
    with open(path) as fh:
        return [json.loads(line) for line in fh if line.strip()]
