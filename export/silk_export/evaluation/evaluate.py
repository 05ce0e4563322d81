# SPDX-License-Identifier: MIT
"""`silk-export eval`: metrics (metrics.py) and structure (structure.py) for a generated mesh
against a reference, or for folders of them matched by file stem; meshes read through libsilk."""

from __future__ import annotations

from pathlib import Path

import numpy as np

import silk_mesh
from ..data.mesh_files import is_mesh_file
from .metrics import compare_meshes
from .structure import mesh_structure

MEAN_KEYS = ("cd", "hd", "nc", "abs_nc")
RATE_KEYS = ("manifold", "watertight", "orientation_consistent")


def _stem(p: Path) -> str:
    name = p.name[:-3] if p.name.lower().endswith(".gz") else p.name
    return name.rsplit(".", 1)[0]


def evaluate_pair(generated: Path, reference: Path | None, n_points: int = 10000, seed: int = 0) -> dict:
    vg, fg = silk_mesh.load_arrays(generated)
    row = {"name": _stem(Path(generated)), "structure": mesh_structure(vg, fg)}
    if reference is not None:
        vr, fr = silk_mesh.load_arrays(reference)
        row["reference_faces"] = int(fr.shape[0])
        row["metrics"] = compare_meshes(vg, fg, vr, fr, n_points, seed)
    return row


def summarize(rows: list[dict]) -> dict:
    ok = [r for r in rows if "error" not in r]
    out = {"meshes": len(rows), "evaluated": len(ok)}
    with_m = [r for r in ok if "metrics" in r]
    for k in MEAN_KEYS:
        if with_m:
            out[f"mean_{k}"] = float(np.mean([r["metrics"][k] for r in with_m]))
    for k in RATE_KEYS:
        if ok:
            out[f"rate_{k}"] = float(np.mean([r["structure"][k] for r in ok]))
    if ok:
        out["mean_faces"] = float(np.mean([r["structure"]["faces"] for r in ok]))
        out["mean_components"] = float(np.mean([r["structure"]["components"] for r in ok]))
    return out


def evaluate_paths(generated: Path, reference: Path | None = None, n_points: int = 10000, seed: int = 0) -> dict:
    generated = Path(generated)
    if generated.is_file():
        rows = [evaluate_pair(generated, reference, n_points, seed)]
        return {"summary": summarize(rows), "meshes": rows}
    refs = {}
    if reference is not None:
        refs = {_stem(p): p for p in Path(reference).iterdir() if p.is_file() and is_mesh_file(p)}
    rows = []
    for g in sorted(p for p in generated.iterdir() if p.is_file() and is_mesh_file(p)):
        r = refs.get(_stem(g)) if reference is not None else None
        if reference is not None and r is None:
            continue
        try:
            rows.append(evaluate_pair(g, r, n_points, seed))
        except (silk_mesh.SilkError, ValueError) as e:
            rows.append({"name": _stem(g), "error": str(e)})
    return {"summary": summarize(rows), "meshes": rows}
