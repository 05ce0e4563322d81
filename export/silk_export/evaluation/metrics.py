# SPDX-License-Identifier: MIT
"""Geometric metrics between two meshes (Mesh Silksong paper, Sec. 4): both meshes normalised to
±0.95 (token_format.md §2.1), n area-weighted surface samples each, then
  CD   = ½·(mean_a d(a,B) + mean_b d(b,A))      (Euclidean distance to the nearest sample)
  HD   = max(max_a d(a,B), max_b d(b,A))
  NC   = ½·(mean_a n_a·n_nn(a) + mean_b n_b·n_nn(b))   (face normals of the nearest samples)
  |NC| = the same with |n·n'| (ignores orientation)."""

from __future__ import annotations

import numpy as np
import torch

from ..data.pointcloud import point_cloud, sample_surface


def nearest(a: np.ndarray, b: np.ndarray, chunk: int = 1024) -> tuple[np.ndarray, np.ndarray]:
    """For each row of a: (distance to the nearest row of b, its index). The search uses the
    fast matrix form; the reported distances are recomputed exactly for the chosen pairs."""
    ta, tb = torch.from_numpy(np.asarray(a, np.float64)), torch.from_numpy(np.asarray(b, np.float64))
    fa, fb = ta.float(), tb.float()
    idx = torch.cat([torch.cdist(fa[i : i + chunk], fb).argmin(dim=1) for i in range(0, fa.shape[0], chunk)])
    dist = torch.linalg.vector_norm(ta - tb[idx], dim=1)
    return dist.numpy(), idx.numpy()


def surface_samples(v, f, n: int, seed: int, normalize: bool = True) -> tuple[np.ndarray, np.ndarray]:
    """n area-weighted surface samples and their face normals (float64 [n, 3] each), in libsilk's
    normalised frame (±0.95, normalised there once) or, with normalize=False, in the mesh's own."""
    rng = np.random.default_rng(seed)
    if not normalize:
        return sample_surface(v, f, n, rng)
    rows = point_cloud(v, f, rng, n=n, noise=False)
    return rows[:, :3].astype(np.float64), rows[:, 3:].astype(np.float64)


def compare_meshes(v_a, f_a, v_b, f_b, n_points: int = 10000, seed: int = 0, normalize: bool = True) -> dict:
    """CD, HD, NC, |NC| between mesh A and mesh B (see the module docstring)."""
    pa, na = surface_samples(v_a, f_a, n_points, seed, normalize)
    pb, nb = surface_samples(v_b, f_b, n_points, seed, normalize)
    d_ab, i_ab = nearest(pa, pb)
    d_ba, i_ba = nearest(pb, pa)
    dot_ab = np.einsum("ij,ij->i", na, nb[i_ab])
    dot_ba = np.einsum("ij,ij->i", nb, na[i_ba])
    return {
        "cd": float(0.5 * (d_ab.mean() + d_ba.mean())),
        "hd": float(max(d_ab.max(), d_ba.max())),
        "nc": float(0.5 * (dot_ab.mean() + dot_ba.mean())),
        "abs_nc": float(0.5 * (np.abs(dot_ab).mean() + np.abs(dot_ba).mean())),
        "cd_a_to_b": float(d_ab.mean()),
        "cd_b_to_a": float(d_ba.mean()),
    }
