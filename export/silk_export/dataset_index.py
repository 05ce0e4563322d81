"""`silk-export dataset`: one pass over a mesh collection through libsilk, writing index.jsonl
(key, file, split, faces, token count, refusal) that training reads. Tokens are not stored:
training tokenizes online after augmentation."""
from __future__ import annotations

import json
import time
from collections import Counter
from pathlib import Path

from tqdm import tqdm

from . import libsilk
from .mesh_files import list_meshes
from .paths import shared_dir
from .splits import DevExclusion, assign_split, load_dev_exclusion, shape_key


def dev_exclusion(dev_dir: Path | None, pmd_root: Path | None = None) -> DevExclusion:
    """Dev corpus paths and shape keys (from its OBJ files and, when present, the original PMDs)."""
    dev_dir = Path(dev_dir) if dev_dir else shared_dir() / "corpus" / "dev"
    ex = load_dev_exclusion(dev_dir, libsilk.load_arrays)
    if pmd_root is not None:
        for zp in sorted(ex.zip_paths):
            p = Path(pmd_root) / zp
            if p.is_file():
                v, f = libsilk.load_arrays(p)
                ex.shape_keys.add(shape_key(v, f.shape[0]))
    return ex


def index_one(key: str, path: Path, root: Path, dev: DevExclusion) -> dict:
    row = {"key": key, "file": path.relative_to(root).as_posix()}
    try:
        with libsilk.Mesh.load(path) as m:
            v = m.positions()
            n_faces = m.triangle_count()
            row.update(vertices=int(v.shape[0]), faces=int(n_faces))
            row["split"] = assign_split(key, shape_key(v, n_faces), dev)
            tokens, stats = libsilk.encode(m)
            row.update(tokens=int(tokens.size), processed_faces=int(stats["processed_faces"]),
                       layers=int(stats["layers"]), max_layer_size=int(stats["max_layer_size"]),
                       refused=None)
    except libsilk.SilkRefused as e:
        row.update(tokens=None, refused=e.reason)
    except libsilk.SilkError as e:
        row.update(tokens=None, refused=f"error:{e.name}")
    if "split" not in row:
        row["split"] = assign_split(key, "", dev)
    return row


def build_index(root: Path, out_dir: Path, dev_dir: Path | None = None, limit: int | None = None) -> dict:
    root, out_dir = Path(root), Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    files = list_meshes(root)
    if limit:
        files = files[:limit]
    dev = dev_exclusion(dev_dir, pmd_root=root if (root / "art" / "meshes").is_dir() else None)
    t0 = time.time()
    rows = [index_one(k, p, root, dev) for k, p in tqdm(files, desc="index", unit="mesh")]
    tmp = out_dir / "index.jsonl.tmp"
    with open(tmp, "w") as fh:
        for r in rows:
            fh.write(json.dumps(r) + "\n")
    tmp.replace(out_dir / "index.jsonl")
    summary = {
        "root": str(root), "meshes": len(rows), "seconds": round(time.time() - t0, 1),
        "splits": dict(Counter(r["split"] for r in rows)),
        "encodable_by_split": dict(Counter(r["split"] for r in rows if r["refused"] is None)),
        "refusals": dict(Counter(r["refused"] for r in rows if r["refused"])),
    }
    (out_dir / "summary.json").write_text(json.dumps(summary, indent=2) + "\n")
    return summary


def read_index(path: Path) -> list[dict]:
    with open(path) as fh:
        return [json.loads(line) for line in fh if line.strip()]
