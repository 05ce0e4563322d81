# SPDX-License-Identifier: MIT
"""How far a quantized decoder moves from the fp32 one, and how fast each runs: teacher-forced
top-1 agreement and KL(fp32 || variant) on sequences the fp32 model itself decodes greedily from
fixed probe point clouds, plus milliseconds per generated token. The importer picks the fastest
variant that passes (`choose`)."""

from __future__ import annotations

import time
from pathlib import Path

import numpy as np

from .decode import DecoderState, greedy, session, teacher_forced

MIN_TOP1 = 0.97
MAX_MEAN_KL = 0.05


def probe_points(n: int) -> list[np.ndarray]:
    """Two deterministic clouds [1,n,6] (sphere radius 0.9; box ±0.9 with face normals), rounded to
    float16 like the official pre-processing."""
    rng = np.random.default_rng(0)
    v = rng.normal(size=(n, 3))
    v /= np.linalg.norm(v, axis=1, keepdims=True)
    sphere = np.concatenate([0.9 * v, v], axis=1)
    axis, sign = rng.integers(0, 3, n), rng.choice([-1.0, 1.0], n)
    xyz = rng.uniform(-0.9, 0.9, size=(n, 3))
    xyz[np.arange(n), axis] = 0.9 * sign
    nrm = np.zeros((n, 3))
    nrm[np.arange(n), axis] = sign
    box = np.concatenate([xyz, nrm], axis=1)
    return [c.astype(np.float16).astype(np.float32)[None] for c in (sphere, box)]


def _log_softmax(x: np.ndarray) -> np.ndarray:
    x = x.astype(np.float64)
    x = x - x.max(axis=-1, keepdims=True)
    return x - np.log(np.exp(x).sum(axis=-1, keepdims=True))


def _ms_per_token(decoder, cross: np.ndarray, ids: list[int]) -> float:
    state = DecoderState(decoder, cross)
    state.run(ids[:1])
    t0 = time.perf_counter()
    for tok in ids[1:]:
        state.run([tok])
    return 1000.0 * (time.perf_counter() - t0) / max(1, len(ids) - 1)


def measure(
    folder: Path,
    variants: dict[str, str],
    bos_id: int,
    eos_id: int,
    n_points: int,
    n_tokens: int = 32,
    threads: int = 1,
) -> dict:
    """variants: name -> decoder file in folder ("decoder" = the fp32 reference must be one)."""
    folder = Path(folder)
    enc = session(folder / "encoder.onnx", threads)
    crosses = [enc.run(None, {"points": p})[0] for p in probe_points(n_points)]
    del enc
    ref = session(folder / variants["decoder"], threads)
    seqs = [[bos_id] + greedy(ref, c, bos_id, eos_id, n_tokens) for c in crosses]
    ref_logp = [_log_softmax(teacher_forced(ref, c, s)) for c, s in zip(crosses, seqs)]
    del ref
    out = {}
    for name, file in variants.items():
        dec = session(folder / file, threads)
        agree, kls = [], []
        for c, s, lp in zip(crosses, seqs, ref_logp):
            lq = _log_softmax(teacher_forced(dec, c, s))
            agree.append(lp.argmax(-1) == lq.argmax(-1))
            kls.append((np.exp(lp) * (lp - lq)).sum(-1))
        agree, kls = np.concatenate(agree), np.concatenate(kls)
        out[name] = {
            "file": file,
            "top1_agreement": round(float(agree.mean()), 4),
            "kl_mean": float(f"{kls.mean():.3g}"),
            "kl_max": float(f"{kls.max():.3g}"),
            "ms_per_token": round(_ms_per_token(dec, crosses[0], seqs[0]), 2),
            "positions": int(agree.size),
        }
        del dec
    return out


def passes(fig: dict) -> bool:
    return fig["top1_agreement"] >= MIN_TOP1 and fig["kl_mean"] <= MAX_MEAN_KL


def choose(figures: dict) -> str:
    """The fastest variant that passes; the fp32 "decoder" is the fallback."""
    ok = [name for name, fig in figures.items() if name == "decoder" or passes(fig)]
    return min(ok, key=lambda name: figures[name]["ms_per_token"])
