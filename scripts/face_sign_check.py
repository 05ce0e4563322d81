# SPDX-License-Identifier: MIT
"""Why NC stays near 0 (issue 33): for each generated mesh of an eval_quality.sh set, how much of
each part faces against the part's own majority (the input's normals nearest each face, area
weighted) and how many interior edges join two faces that face opposite sides of the input.
A part here is a surface patch (faces joined by shared edges), the unit `--orient input` turns.

    PYTHONPATH=export SILK_LIBRARY=build/engine/libsilk.so python3 scripts/face_sign_check.py OUT/test

Per mesh and as means: NC and |NC| over the faces (area weighted, each face against the input
normal nearest its centroid), "disagree" (the share of area whose sign differs from its part's
area-weighted majority: what `--orient input`, which turns whole patches, cannot fix), "edge flips"
(interior edges whose two faces disagree in sign) and the same with both faces within 60 deg of
the input's normals (what the signed pair score of commit 18e0c90 scored past 1)."""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

import silk_mesh
from silk_export.evaluation.metrics import nearest, surface_samples
from silk_export.evaluation.structure import surface_patches


def normalised(v: np.ndarray) -> np.ndarray:
    lo, hi = v.min(0), v.max(0)
    return (v - (lo + hi) / 2) * (1.9 / (hi - lo).max())


def edge_faces(faces: np.ndarray) -> dict:
    """The faces on each edge."""
    edges: dict = {}
    for i, f in enumerate(faces.tolist()):
        for k in range(3):
            edges.setdefault((min(f[k], f[k - 2]), max(f[k], f[k - 2])), []).append(i)
    return edges


def check(generated: Path, reference: Path) -> dict:
    vg, fg = silk_mesh.load_arrays(generated)
    vr, fr = silk_mesh.load_arrays(reference)
    vg, vr = normalised(np.asarray(vg, float)), normalised(np.asarray(vr, float))
    fg = np.asarray(fg)
    ref_points, ref_normals = surface_samples(vr, np.asarray(fr), 20000, 0, normalize=False)
    a, b, c = vg[fg[:, 0]], vg[fg[:, 1]], vg[fg[:, 2]]
    cross = np.cross(b - a, c - a)
    area = np.linalg.norm(cross, axis=1) / 2
    unit = np.divide(cross, 2 * area[:, None], out=np.zeros_like(cross), where=area[:, None] > 0)
    _, idx = nearest((a + b + c) / 3, ref_points)
    cos = np.einsum("ij,ij->i", unit, ref_normals[idx])
    part, edges = surface_patches(fg), edge_faces(fg)
    vote: dict = {}
    for p, w in zip(part, area * cos):
        vote[p] = vote.get(p, 0.0) + w
    sign = np.array([1.0 if vote[p] >= 0 else -1.0 for p in part])
    total = area.sum()
    pairs = [e for e in edges.values() if len(e) == 2]
    flips = [cos[x] * cos[y] < 0 for x, y in pairs]
    strong = [cos[x] * cos[y] < 0 and min(abs(cos[x]), abs(cos[y])) > 0.5 for x, y in pairs]
    return {
        "nc": float((area * cos).sum() / total),
        "abs_nc": float((area * np.abs(cos)).sum() / total),
        "disagree": float(area[cos * sign < 0].sum() / total),
        "edge_flips": float(np.mean(flips)) if pairs else 0.0,
        "strong_flips": float(np.mean(strong)) if pairs else 0.0,
        "parts": len(vote),
    }


def main() -> int:
    if len(sys.argv) != 2:
        print(__doc__, file=sys.stderr)
        return 2
    d = Path(sys.argv[1])
    rows = []
    for g in sorted((d / "generated").glob("*.obj")):
        refs = sorted((d / "reference").glob(g.stem + ".*"))
        if not refs:
            print(f"face_sign_check: {g.name}: no reference in {d / 'reference'}", file=sys.stderr)
            return 1
        r = check(g, refs[0])
        rows.append(r)
        print(f"{g.stem:32s} " + " ".join(f"{k} {v:.3f}" if isinstance(v, float) else f"{k} {v}" for k, v in r.items()))
    if not rows:
        print(f"face_sign_check: no generated OBJ in {d / 'generated'}", file=sys.stderr)
        return 1
    keys = ("nc", "abs_nc", "disagree", "edge_flips", "strong_flips")
    print("MEAN " + " ".join(f"{k} {np.mean([r[k] for r in rows]):.3f}" for k in keys))
    return 0


if __name__ == "__main__":
    sys.exit(main())
