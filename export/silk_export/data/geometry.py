# SPDX-License-Identifier: MIT
"""Numpy geometry shared by the data pipeline and evaluation: the token_format.md §2.1 bounding-box
normalisation (surface sampling is libsilk's, see pointcloud.py)."""

from __future__ import annotations

import numpy as np


def normalize_vertices(v: np.ndarray, bound: float = 0.95) -> np.ndarray:
    """token_format.md §2.1 in float64: centre the bounding box of ALL vertices, longest side to 2*bound."""
    v = np.asarray(v, dtype=np.float64)
    if v.shape[0] == 0:
        return v.copy()
    lo, hi = v.min(axis=0), v.max(axis=0)
    center = (hi + lo) / 2
    extent = float((hi - lo).max())
    scale = (2 * bound) / extent if extent > 0 else 1.0
    return (v - center) * scale
