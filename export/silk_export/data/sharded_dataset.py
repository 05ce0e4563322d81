# SPDX-License-Identifier: MIT
"""Training's view of a merged dataset folder (dataset.json + shards): the selected index rows,
each mesh's arrays and cached tokens read from the memory-mapped shards (no mesh files, no
per-mesh cache in memory), with the same `sample()` as samples.MeshCache."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np

from .dataset_index import DATASET_FORMAT, read_index
from .samples import Sample, make_sample
from .shard_store import Shard


def is_dataset(path: Path) -> bool:
    return (Path(path) / "dataset.json").is_file()


def dataset_rows(path: Path) -> list[dict]:
    info = json.loads((Path(path) / "dataset.json").read_text())
    if info.get("format") != DATASET_FORMAT:
        raise ValueError(f"{path}: dataset.json is not {DATASET_FORMAT}")
    return read_index(Path(path) / "index.jsonl")


class ShardedSource:
    def __init__(self, path: Path, rows: list[dict], points_kind: str = "silk"):
        self.path = Path(path)
        self.rows = rows
        self.points_kind = points_kind
        names = json.loads((self.path / "dataset.json").read_text())["shards"]
        self._names = names
        self._shards: dict[int, Shard] = {}  # opened lazily (cheap; also in DataLoader workers)

    def __len__(self) -> int:
        return len(self.rows)

    def _shard(self, s: int) -> Shard:
        if s not in self._shards:
            self._shards[s] = Shard(self.path / self._names[s])
        return self._shards[s]

    def arrays(self, i: int) -> tuple[np.ndarray, np.ndarray]:
        r = self.rows[i]
        return self._shard(r["shard"]).mesh_arrays(r["slot"])

    def tokens(self, i: int) -> np.ndarray:
        r = self.rows[i]
        return self._shard(r["shard"]).mesh_tokens(r["slot"])

    def sample(
        self, i: int, rng: np.random.Generator, max_tokens: int, augment: bool = True, n_points: int = 4096
    ) -> Sample:
        """Without augmentation the cached tokens are used (no tokenisation at all)."""
        v, f = self.arrays(i)
        cached = None if augment else self.tokens(i)
        return make_sample(
            v,
            f,
            rng,
            max_tokens,
            augment,
            n_points,
            key=self.rows[i]["key"],
            tokens=cached,
            points_kind=self.points_kind,
        )
