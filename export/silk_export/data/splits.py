# SPDX-License-Identifier: MIT
"""Deterministic train/val/test split and the dev-corpus exclusion.

Split by SHA-1 of a mesh's path inside public.zip (UTF-8): first hex digit 0–d train, e val,
f test. Dev-corpus meshes, and any mesh with the same shape (dev corpus README: same set of
vertex positions rounded to 1e-5 and same face count), get the split "dev" and never train."""

from __future__ import annotations

import csv
import hashlib
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

TRAIN, VAL, TEST, DEV = "train", "val", "test", "dev"


def hash_split(zip_path: str) -> str:
    digit = hashlib.sha1(zip_path.encode("utf-8")).hexdigest()[0]
    return TEST if digit == "f" else VAL if digit == "e" else TRAIN


def shape_key(positions: np.ndarray, n_faces: int) -> str:
    """Identity of a shape: the set of positions rounded to 1e-5, plus the face count."""
    q = np.round(np.asarray(positions, np.float64) * 1e5).astype(np.int64).reshape(-1, 3)
    q = np.unique(q, axis=0) if q.shape[0] else q  # sorted set of rows
    h = hashlib.sha1(np.ascontiguousarray(q).tobytes()).hexdigest()
    return f"{h}:{int(n_faces)}"


@dataclass
class DevExclusion:
    """Paths (inside public.zip) and shape keys of the dev corpus."""

    zip_paths: set = field(default_factory=set)
    shape_keys: set = field(default_factory=set)

    def excludes(self, zip_path: str, key: str) -> bool:
        return zip_path in self.zip_paths or key in self.shape_keys


def read_dev_manifest(manifest: Path) -> list[dict]:
    """Rows of corpus/dev/MANIFEST.tsv with `zip_path` = source without its 'package:' prefix."""
    with open(manifest, newline="", encoding="utf-8") as fh:
        rows = list(csv.DictReader(fh, delimiter="\t"))
    for r in rows:
        r["zip_path"] = r["source"].split(":", 1)[1] if ":" in r["source"] else r["source"]
    return rows


def load_dev_exclusion(dev_dir: Path, load_arrays) -> DevExclusion:
    """Reads the manifest and the dev OBJ files (through `load_arrays`, i.e. libsilk)."""
    ex = DevExclusion()
    for r in read_dev_manifest(dev_dir / "MANIFEST.tsv"):
        ex.zip_paths.add(r["zip_path"])
        v, f = load_arrays(dev_dir / r["file"])
        ex.shape_keys.add(shape_key(v, f.shape[0]))
    return ex


def assign_split(zip_path: str, key: str, dev: DevExclusion) -> str:
    return DEV if dev.excludes(zip_path, key) else hash_split(zip_path)
