# SPDX-License-Identifier: MIT
"""Training augmentation on raw vertices (numpy): per-axis scale in [0.75, 0.95] and a rotation
about the up axis (y) in 30° steps. Tokenization re-normalises afterwards (token_format.md §2.1)."""

from __future__ import annotations

import numpy as np

SCALE_RANGE = (0.75, 0.95)
ROTATION_STEP_DEG = 30


def rotation_y(degrees: float) -> np.ndarray:
    t = np.radians(degrees)
    c, s = np.cos(t), np.sin(t)
    return np.array([[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]])


def augment_vertices(v: np.ndarray, rng: np.random.Generator) -> tuple[np.ndarray, dict]:
    """Returns (augmented float64 vertices, {'scale': [3], 'rotation_deg': k*30})."""
    scale = rng.uniform(*SCALE_RANGE, size=3)
    deg = ROTATION_STEP_DEG * int(rng.integers(0, 360 // ROTATION_STEP_DEG))
    out = (np.asarray(v, np.float64) * scale) @ rotation_y(deg).T
    return out, {"scale": scale.tolist(), "rotation_deg": deg}
