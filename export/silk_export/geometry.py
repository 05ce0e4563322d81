"""Numpy geometry shared by the data pipeline and evaluation: the spec §2.1 bounding-box
normalisation, per-face areas and normals."""
from __future__ import annotations

import numpy as np


def normalize_vertices(v: np.ndarray, bound: float = 0.95) -> np.ndarray:
    """Spec §2.1 in float64: centre the bounding box of ALL vertices, longest side to 2*bound."""
    v = np.asarray(v, dtype=np.float64)
    if v.shape[0] == 0:
        return v.copy()
    lo, hi = v.min(axis=0), v.max(axis=0)
    center = (hi + lo) / 2
    extent = float((hi - lo).max())
    scale = (2 * bound) / extent if extent > 0 else 1.0
    return (v - center) * scale


def face_cross(v: np.ndarray, f: np.ndarray) -> np.ndarray:
    """Un-normalised face normals (cross products), float64 [F,3]."""
    a, b, c = v[f[:, 0]], v[f[:, 1]], v[f[:, 2]]
    return np.cross(b - a, c - a)


def face_areas_normals(v: np.ndarray, f: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(areas [F], unit normals [F,3]; zero vector for degenerate faces)."""
    cr = face_cross(np.asarray(v, np.float64), np.asarray(f, np.int64))
    norm = np.linalg.norm(cr, axis=1)
    normals = np.zeros_like(cr)
    ok = norm > 0
    normals[ok] = cr[ok] / norm[ok, None]
    return 0.5 * norm, normals
