# SPDX-License-Identifier: MIT
"""`silk-export generate`: generated/<stem>.obj beside reference/<stem>.obj for `silk-export eval`,
always through libsilk's runtime in this process (the grammar-constrained sampling chain silkgen,
the C API and the Blender add-on run: top-p, surface guidance, best of N, silkgen's seeds). A model
folder runs as it is; a checkpoint is first exported to a temporary model folder (fp32 decoder, no
model.json sampling, so libsilk's defaults), so evaluating a checkpoint measures what its export
would ship and `silkgen --seed S` on that export gives the same ids. There is no second sampler."""

from __future__ import annotations

import json
import tempfile
from pathlib import Path

import numpy as np
from tqdm import tqdm

import silk_mesh
from ..checkpoint import model_from_checkpoint
from ..data.normalization import normalize_vertices
from ..json_io import write_json
from ..onnx.export import export_model

SETTINGS = ("temperature", "top_k", "top_p", "surface_tolerance", "candidates", "orient")


def pick_from_index(index: Path, root: Path, split: str, limit: int, max_tokens: int) -> list[Path]:
    """`limit` encodable meshes of one split, evenly spaced over the split sorted by token count."""
    from ..data.dataset_index import read_index

    rows = sorted(
        (
            r
            for r in read_index(index)
            if r["split"] == split and r.get("refused") is None and r.get("tokens") and r["tokens"] <= max_tokens
        ),
        key=lambda r: (r["tokens"], r["key"]),
    )
    if limit and len(rows) > limit:
        rows = [rows[round(i * (len(rows) - 1) / (limit - 1))] for i in range(limit)] if limit > 1 else rows[:1]
    return [Path(root) / r["file"] for r in rows]


def export_checkpoint(checkpoint: Path, out_dir: Path) -> None:
    """The model folder `silk-export export --no-int8` writes (NaN / Inf weights refused)."""
    model, ck = model_from_checkpoint(Path(checkpoint))
    export_model(
        model, out_dir, {"steps": ck["step"], "data": None, "seed": ck.get("args", {}).get("seed")}, int8=False
    )


def generate_paths(model: Path, inputs: list[Path], out_dir: Path, seed: int = 0, threads: int = 1, **params) -> dict:
    """Generates one mesh per input with libsilk (see the module docstring) and writes
    generate.json. model: a model folder or a checkpoint file. params: silk_generate_params by
    name (max_tokens, temperature, top_k, top_p, surface_tolerance, candidates); None or absent =
    the model folder's defaults (model.json "sampling", else libsilk's)."""
    params = {k: v for k, v in params.items() if v is not None}
    if not Path(model).exists():
        raise FileNotFoundError(f"{model}: no such model folder or checkpoint")
    if Path(model).is_dir():
        summary = _generate(Path(model), inputs, Path(out_dir), seed, threads, params)
    else:
        with tempfile.TemporaryDirectory(prefix="silk-generate-") as tmp:
            export_checkpoint(Path(model), Path(tmp))
            summary = _generate(Path(tmp), inputs, Path(out_dir), seed, threads, params)
        summary = {"checkpoint": str(model), **summary}
    write_json(Path(out_dir) / "generate.json", summary, "null")
    return summary


def _generate(model_dir: Path, inputs: list[Path], out_dir: Path, seed: int, threads: int, params: dict) -> dict:
    gen_dir, ref_dir = out_dir / "generated", out_dir / "reference"
    rows, settings = [], None
    with silk_mesh.Model(model_dir, threads=threads) as model, silk_mesh.Generator(model) as gen:
        gen_dir.mkdir(parents=True, exist_ok=True)  # only once the model loaded
        ref_dir.mkdir(parents=True, exist_ok=True)
        for p in tqdm(inputs, desc="generate", unit="mesh"):
            row = {"name": p.name.split(".")[0]}
            try:
                row.update(_one(gen, p, ref_dir / f"{row['name']}.obj", gen_dir / f"{row['name']}.obj", seed, params))
                if settings is None:  # what libsilk resolved (explicit values over the model's defaults)
                    s = json.loads(gen.report_json())["settings"]
                    settings = {k: s[k] for k in SETTINGS if k in s}
            except silk_mesh.SilkError as e:
                row.update(eos=False, error=str(e)[-300:])
            rows.append(row)
    return {
        "runtime": "libsilk",
        "inputs": len(rows),
        "settings": settings or {},
        "eos_rate": float(np.mean([r["eos"] for r in rows])) if rows else 0.0,
        "decoded_with_faces": sum(1 for r in rows if r.get("faces")),
        "meshes": rows,
    }


def _one(gen, path: Path, reference: Path, generated: Path, seed: int, params: dict) -> dict:
    """Writes the input normalised by libsilk's transform (the frame generated meshes come in)
    and the generated mesh (when it has faces); returns its generate.json row."""
    v, f = silk_mesh.load_arrays(path)
    with silk_mesh.Mesh(normalize_vertices(v, f), f) as ref:
        ref.save(reference)
    with silk_mesh.Mesh.load(path) as src:
        mesh, _, st = gen.run(src, seed=seed, **params)
    with mesh:
        if mesh.triangle_count:
            mesh.save(generated)
    keep = ("tokens", "faces", "stop_reason", "tokens_per_second", "guided_tokens", "guidance_fallbacks")
    row = {k: st[k] for k in (*keep, "candidates", "chosen_candidate", "score")}
    return {**row, "eos": st["stop_reason"] == "eos", "seconds": st["seconds_total"]}
