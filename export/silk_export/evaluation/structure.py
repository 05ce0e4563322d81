# SPDX-License-Identifier: MIT
"""Structural figures of one mesh, measured after welding bit-identical positions (as the dev
corpus manifest does): faces, connected components (faces sharing a vertex), edge-manifold,
watertight, and whether the faces are consistently oriented across every 2-face edge."""

from __future__ import annotations

from collections import Counter

import numpy as np


def _roots(n: int, pairs) -> list[int]:
    """Each of n items' group (a representative) after joining every pair (union-find)."""
    parent = list(range(n))

    def find(x: int) -> int:
        while parent[x] != x:
            parent[x] = parent[parent[x]]
            x = parent[x]
        return x

    for a, b in pairs:
        parent[find(b)] = find(a)
    return [find(x) for x in range(n)]


def _components(n_vertices: int, faces: np.ndarray) -> int:
    roots = _roots(n_vertices, ((a, x) for a, b, c in faces.tolist() for x in (b, c)))
    return len({roots[int(x)] for x in np.unique(faces)})


def surface_patches(faces) -> list[int]:
    """Each face's surface patch: faces joined by shared edges (the unit `--orient input` turns).
    Faces are (a, b, c) vertex indices; the result is one representative face index per face."""
    first: dict = {}
    pairs = []
    for i, f in enumerate(np.asarray(faces, np.int64).reshape(-1, 3).tolist()):
        for k in range(3):
            e = (min(f[k], f[k - 2]), max(f[k], f[k - 2]))
            if e in first:
                pairs.append((first[e], i))
            else:
                first[e] = i
    return _roots(len(faces), pairs)


def mesh_structure(v: np.ndarray, f: np.ndarray) -> dict:
    v = np.asarray(v, np.float64)
    f = np.asarray(f, np.int64).reshape(-1, 3)
    if v.shape[0]:
        _, weld = np.unique(v, axis=0, return_inverse=True)
        weld = weld.reshape(-1)
        fw = weld[f] if f.size else f
    else:
        fw = f
    proper = fw[(fw[:, 0] != fw[:, 1]) & (fw[:, 1] != fw[:, 2]) & (fw[:, 0] != fw[:, 2])] if fw.size else fw
    directed = Counter()
    for a, b, c in proper.tolist():
        directed[(a, b)] += 1
        directed[(b, c)] += 1
        directed[(c, a)] += 1
    undirected = Counter()
    for (a, b), k in directed.items():
        undirected[(min(a, b), max(a, b))] += k
    manifold = all(k <= 2 for k in undirected.values())
    watertight = len(undirected) > 0 and all(k == 2 for k in undirected.values())
    oriented = all(
        directed.get((a, b), 0) == 1 and directed.get((b, a), 0) == 1 for (a, b), k in undirected.items() if k == 2
    )
    return {
        "faces": int(f.shape[0]),
        "vertices": int(v.shape[0]),
        "components": _components(int(fw.max()) + 1, proper) if proper.size else 0,
        "manifold": bool(manifold),
        "watertight": bool(watertight),
        "orientation_consistent": bool(oriented),
        "boundary_edges": int(sum(1 for k in undirected.values() if k == 1)),
        "nonmanifold_edges": int(sum(1 for k in undirected.values() if k > 2)),
    }
