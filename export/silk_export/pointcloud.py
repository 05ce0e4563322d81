"""Area-weighted surface samples with face normals (numpy): the model's point-cloud condition
[N, 6] (xyz then unit normal), with optional Gaussian jitter as in training."""
from __future__ import annotations

import numpy as np

from .geometry import face_areas_normals

N_POINTS = 4096
NOISE_PROBABILITY = 0.5
NOISE_STD = 0.01


def sample_surface(v: np.ndarray, f: np.ndarray, n: int, rng: np.random.Generator
                   ) -> tuple[np.ndarray, np.ndarray]:
    """n points uniformly distributed over the surface area, and their faces' unit normals."""
    v = np.asarray(v, np.float64)
    f = np.asarray(f, np.int64)
    areas, normals = face_areas_normals(v, f)
    total = areas.sum()
    if f.shape[0] == 0 or total <= 0:
        raise ValueError("mesh has no surface area to sample")
    face = rng.choice(f.shape[0], size=n, p=areas / total)
    r1, r2 = rng.random(n), rng.random(n)
    s1 = np.sqrt(r1)
    w0, w1, w2 = 1 - s1, s1 * (1 - r2), s1 * r2  # uniform barycentrics
    tri = v[f[face]]
    pts = w0[:, None] * tri[:, 0] + w1[:, None] * tri[:, 1] + w2[:, None] * tri[:, 2]
    return pts, normals[face]


def point_cloud(v_normalized: np.ndarray, f: np.ndarray, rng: np.random.Generator,
                n: int = N_POINTS, noise: bool = True) -> np.ndarray:
    """float32 [n, 6] condition; with noise=True adds N(0, 0.01²) to xyz with probability 0.5."""
    pts, nrm = sample_surface(v_normalized, f, n, rng)
    if noise and rng.random() < NOISE_PROBABILITY:
        pts = pts + rng.normal(0.0, NOISE_STD, size=pts.shape)
    return np.concatenate([pts, nrm], axis=1).astype(np.float32)
