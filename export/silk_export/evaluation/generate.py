# SPDX-License-Identifier: MIT
"""`silk-export generate`: sample token sequences from a checkpoint (PyTorch, KV cache, top-k, no
grammar mask) conditioned on the point cloud of each input mesh and decode them through libsilk,
or run the C++ runtime (grammar-constrained, through libsilk's C API) on an exported model folder;
either way write generated/<stem>.obj beside reference/<stem>.obj for `silk-export eval`."""

from __future__ import annotations

import json
import time
from pathlib import Path

import numpy as np
import torch
from tqdm import tqdm

import silk_mesh
from ..data.geometry import normalize_vertices
from ..data.pointcloud import point_cloud
from ..json_io import write_json
from ..models.architecture import Architecture
from ..checkpoint import model_from_checkpoint


@torch.no_grad()
def sample_tokens(
    model: Architecture, points: np.ndarray, max_tokens: int, temperature: float, top_k: int, generator: torch.Generator
) -> tuple[np.ndarray, bool]:
    """Samples at most max_tokens ids (EOS included) with a model of any registered architecture,
    one Architecture.step per id. points: float32 [N, 6] by the architecture's pre-processing.
    Returns (format ids without BOS/EOS, whether EOS was produced)."""
    model.eval()
    cross = model.encode_points(torch.from_numpy(points).unsqueeze(0))
    past = model.empty_cache()
    ids = torch.tensor([[model.bos_id]])
    out = []
    for pos in range(min(max_tokens, model.cfg.max_seq_len - 1)):  # ids sampled, EOS included
        logits, new = model.step(ids, torch.tensor([[pos]]), past, cross, fused=False)
        past = [(torch.cat([pk, kn], 2), torch.cat([pv, vn], 2)) for (pk, pv), (kn, vn) in zip(past, new)]
        lg = logits[0, -1].clone()
        lg[model.pad_id] = float("-inf")
        if top_k:
            kth = torch.topk(lg, top_k).values[-1]
            lg[lg < kth] = float("-inf")
        probs = torch.softmax(lg / max(temperature, 1e-6), dim=-1)
        tok = int(torch.multinomial(probs, 1, generator=generator))
        if tok == model.eos_id:
            return np.asarray(out, np.int32), True
        out.append(tok)
        ids = torch.tensor([[tok]])
    return np.asarray(out, np.int32), False


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


def generate_paths(
    checkpoint: Path,
    inputs: list[Path],
    out_dir: Path,
    max_tokens: int = 0,
    temperature: float = 0.5,
    top_k: int = 50,
    seed: int = 0,
    threads: int = 1,
) -> dict:
    if threads:
        torch.set_num_threads(threads)  # one token at a time: more threads only add sync cost
    model, _ = model_from_checkpoint(checkpoint)
    gen_dir, ref_dir = Path(out_dir) / "generated", Path(out_dir) / "reference"
    gen_dir.mkdir(parents=True, exist_ok=True)
    ref_dir.mkdir(parents=True, exist_ok=True)
    g = torch.Generator().manual_seed(seed)
    rng = np.random.default_rng(seed)
    rows = []
    for p in tqdm(inputs, desc="generate", unit="mesh"):
        stem = p.name.split(".")[0]
        v, f = silk_mesh.load_arrays(p)
        vn = normalize_vertices(v, 0.95)
        with silk_mesh.Mesh(vn, f) as ref:
            ref.save(ref_dir / f"{stem}.obj")
        t0 = time.time()
        pts = point_cloud(vn, f, rng, n=model.cfg.n_points, noise=False, kind=model.points_kind(model.cfg))
        toks, eos = sample_tokens(model, pts, max_tokens or model.cfg.max_seq_len - 1, temperature, top_k, g)
        row = {"name": stem, "tokens": int(toks.size), "eos": eos, "seconds": round(time.time() - t0, 2)}
        try:
            with silk_mesh.decode(toks) as m:
                row["faces"] = m.triangle_count
                if m.triangle_count:
                    m.save(gen_dir / f"{stem}.obj")
        except silk_mesh.SilkError as e:
            row["decode_error"] = str(e)
        rows.append(row)
    summary = {
        "inputs": len(rows),
        "eos_rate": float(np.mean([r["eos"] for r in rows])) if rows else 0.0,
        "decoded_with_faces": sum(1 for r in rows if r.get("faces")),
        "meshes": rows,
    }
    write_json(Path(out_dir) / "generate.json", summary, "null")
    return summary


def generate_with_runtime(
    model_dir: Path,
    inputs: list[Path],
    out_dir: Path,
    seed: int = 0,
    threads: int = 1,
    max_tokens: int = 0,
    temperature: float | None = None,
    top_k: int | None = None,
    surface_tolerance: int | None = None,
    candidates: int | None = None,
) -> dict:
    """Runs the C++ runtime (grammar-constrained) per input with the exported model, in this
    process through libsilk's C API (the same generation silkgen and the Blender add-on run).
    temperature / top_k / candidates None: the model folder's defaults (model.json "sampling", else
    libsilk's)."""
    gen_dir, ref_dir = Path(out_dir) / "generated", Path(out_dir) / "reference"
    gen_dir.mkdir(parents=True, exist_ok=True)
    ref_dir.mkdir(parents=True, exist_ok=True)
    rows, sampling = [], None
    with silk_mesh.Model(model_dir, threads=threads) as model, silk_mesh.Generator(model) as gen:
        for p in tqdm(inputs, desc="silk runtime", unit="mesh"):
            stem = p.name.split(".")[0]
            v, f = silk_mesh.load_arrays(p)
            with silk_mesh.Mesh(normalize_vertices(v, 0.95), f) as ref:
                ref.save(ref_dir / f"{stem}.obj")
            row = {"name": stem}
            try:
                with silk_mesh.Mesh.load(p) as src:
                    mesh, _, st = gen.run(
                        src,
                        seed=seed,
                        max_tokens=max_tokens,
                        temperature=temperature,
                        top_k=top_k,
                        surface_tolerance=surface_tolerance,
                        candidates=candidates,
                    )
                with mesh:
                    if mesh.triangle_count:
                        mesh.save(gen_dir / f"{stem}.obj")
                row.update(
                    tokens=st["tokens"],
                    eos=st["stop_reason"] == "eos",
                    faces=st["faces"],
                    stop_reason=st["stop_reason"],
                    seconds=st["seconds_total"],
                    tokens_per_second=st["tokens_per_second"],
                    guided_tokens=st["guided_tokens"],
                    guidance_fallbacks=st["guidance_fallbacks"],
                    candidates=st["candidates"],
                    chosen_candidate=st["chosen_candidate"],
                    score=st["score"],
                )
                if sampling is None:  # what libsilk resolved (explicit values over the model's defaults)
                    s = json.loads(gen.report_json())["settings"]
                    sampling = {
                        k: s[k]
                        for k in ("temperature", "top_k", "top_p", "surface_tolerance", "candidates", "orient")
                        if k in s
                    }
            except silk_mesh.SilkError as e:
                row.update(eos=False, decode_error=str(e)[-300:])
            rows.append(row)
    summary = {
        "runtime": "libsilk",
        "inputs": len(rows),
        "settings": sampling or {},
        "eos_rate": float(np.mean([r["eos"] for r in rows])) if rows else 0.0,
        "decoded_with_faces": sum(1 for r in rows if r.get("faces")),
        "meshes": rows,
    }
    write_json(Path(out_dir) / "generate.json", summary, "null")
    return summary
