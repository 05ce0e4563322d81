# SPDX-License-Identifier: MIT
"""The model's point-cloud condition [N, 6] (xyz then unit normal) through libsilk's
pre-processing (silk_points_prepare: the code generation runs, no second copy in numpy), with
optional Gaussian jitter as in training."""

from __future__ import annotations

import numpy as np

import silk_mesh

N_POINTS = 4096
NOISE_PROBABILITY = 0.5
NOISE_STD = 0.01


def _seed(rng: np.random.Generator) -> int:
    return int(rng.integers(0, 2**63))


def sample_surface(v: np.ndarray, f: np.ndarray, n: int, rng: np.random.Generator) -> tuple[np.ndarray, np.ndarray]:
    """n points uniformly distributed over the surface area (in v's own frame), and their faces'
    unit normals (float64 arrays [n, 3])."""
    rows, centre, scale = silk_mesh.prepare_points(v, f, "silk", n_points=n, seed=_seed(rng))
    return rows[:, :3].astype(np.float64) / scale + centre, rows[:, 3:].astype(np.float64)


def point_cloud(
    v: np.ndarray,
    f: np.ndarray,
    rng: np.random.Generator,
    n: int = N_POINTS,
    noise: bool = True,
    kind: str = "silk",
) -> np.ndarray:
    """float32 [n, 6] condition by the `kind` pre-processing ("silk" or "official"), which
    normalises v itself (no caller normalises first); with noise=True adds N(0, 0.01²) to xyz
    with probability 0.5. Raises silk_mesh.SilkError as libsilk refuses (e.g. a zero extent)."""
    rows, _, _ = silk_mesh.prepare_points(v, f, kind, n_points=n, seed=_seed(rng))
    if noise and rng.random() < NOISE_PROBABILITY:
        rows[:, :3] = rows[:, :3] + rng.normal(0.0, NOISE_STD, size=(rows.shape[0], 3))
    return rows
