# SPDX-License-Identifier: MIT
"""The token_format.md §2.1 bounding-box normalisation of numpy arrays by libsilk's transform
(silk_points_prepare's centre and scale), for the evaluation's reference meshes: the rule, and its
refusal of a zero-extent mesh, live only in libsilk."""

from __future__ import annotations

import numpy as np

import silk_mesh

BOUND = 0.95


def normalize_vertices(v: np.ndarray, f: np.ndarray, bound: float = BOUND) -> np.ndarray:
    """float64 positions centred on the bounding box of ALL vertices, longest side 2*bound: libsilk's
    transform applied as libsilk applies it ((v - centre) * scale, one IEEE operation each), so the
    result equals the frame encode tokenizes in. Raises silk_mesh.SilkError as libsilk refuses
    (no faces, a non-finite coordinate, all vertices at one point)."""
    _, centre, scale = silk_mesh.prepare_points(v, f, "silk", n_points=1, normalize_bound=bound)
    return (np.asarray(v, np.float64) - np.asarray(centre, np.float64)) * scale
