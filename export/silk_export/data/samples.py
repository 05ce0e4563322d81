# SPDX-License-Identifier: MIT
"""Online per-sample pipeline: raw mesh -> (augment) -> tokens through libsilk (normalise +
non-manifold processing) -> point cloud through libsilk (the same normalisation, done once there,
so points and tokens share one frame); plus batch collation
(BOS + tokens as input, tokens + EOS as labels, PAD / ignored past the end)."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np
import torch

import silk_mesh
from ..models.architecture import IGNORE_INDEX
from ..vocab import load_vocab
from .augment import augment_vertices
from .normalization import BOUND
from .pointcloud import point_cloud


class TooLong(ValueError):
    """The mesh's token sequence does not fit the model's maximum length."""


@dataclass
class Sample:
    tokens: np.ndarray  # int32 format ids (no BOS/EOS)
    points: np.ndarray  # float32 [N, 6]
    key: str = ""


def make_sample(
    v: np.ndarray,
    f: np.ndarray,
    rng: np.random.Generator,
    max_tokens: int,
    augment: bool = True,
    n_points: int = 4096,
    key: str = "",
    tokens=None,
    points_kind: str = "silk",
) -> Sample:
    """Raises TooLong, silk_mesh.SilkError (refused, e.g. a layer over 200 vertices) or ValueError.
    tokens: the un-augmented mesh's tokens when already known (a dataset cache); augment=False only.
    points_kind: the architecture's point pre-processing (model.json `preprocessing.kind`)."""
    if augment:
        v, _ = augment_vertices(v, rng)
    if tokens is None or augment:
        tokens = np.asarray(
            silk_mesh.encode((v, f), normalize=True, normalize_bound=BOUND, nonmanifold_processing=True), dtype=np.int32
        )
    if tokens.size == 0 or tokens.size > max_tokens:
        raise TooLong(f"{key}: {tokens.size} tokens (max {max_tokens})")
    pts = point_cloud(v, f, rng, n=n_points, noise=augment, kind=points_kind)
    return Sample(tokens, pts, key)


class MeshCache:
    """Raw (positions, triangles) per index row, loaded once through libsilk."""

    def __init__(self, root: Path, rows: list[dict], points_kind: str = "silk"):
        self.root = Path(root)
        self.rows = rows
        self.points_kind = points_kind
        self._arrays: dict[int, tuple[np.ndarray, np.ndarray]] = {}

    def __len__(self) -> int:
        return len(self.rows)

    def arrays(self, i: int) -> tuple[np.ndarray, np.ndarray]:
        if i not in self._arrays:
            self._arrays[i] = silk_mesh.load_arrays(self.root / self.rows[i]["file"])
        return self._arrays[i]

    def sample(
        self, i: int, rng: np.random.Generator, max_tokens: int, augment: bool = True, n_points: int = 4096
    ) -> Sample:
        v, f = self.arrays(i)
        return make_sample(
            v, f, rng, max_tokens, augment, n_points, key=self.rows[i]["key"], points_kind=self.points_kind
        )


def collate(samples: list[Sample]) -> dict[str, torch.Tensor]:
    vocab = load_vocab()
    s = max(x.tokens.size for x in samples) + 1
    b = len(samples)
    ids = torch.full((b, s), vocab.pad_id, dtype=torch.int64)
    labels = torch.full((b, s), IGNORE_INDEX, dtype=torch.int64)
    for r, x in enumerate(samples):
        t = torch.from_numpy(x.tokens.astype(np.int64))
        ids[r, 0] = vocab.bos_id
        ids[r, 1 : t.numel() + 1] = t
        labels[r, : t.numel()] = t
        labels[r, t.numel()] = vocab.eos_id
    points = torch.from_numpy(np.stack([x.points for x in samples]))
    return {
        "input_ids": ids,
        "labels": labels,
        "points": points,
        "n_tokens": int(sum(x.tokens.size + 1 for x in samples)),
    }
