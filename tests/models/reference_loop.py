#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Independent check of the C++ generation loop (engine/runtime) against onnxruntime's Python
API: given a trace written by `silkgen --trace` (the encoder points, every generated id, whether
the grammar forced it, the legal set it was sampled from and, under soft face guidance, the
logit penalties the chain subtracted), this script

  1. runs encoder.onnx on the same points,
  2. replays the generation with its own KV cache (compact per-layer arrays that onnxruntime
     returns grown by the new rows, i.e. the unshared mode of the contract; no shared code) and its
     own copy of the sampling chain (SplitMix64, temperature -> top-k -> top-p) and requires
     every sampled id to come out identical,
  3. runs decoder.onnx once over the whole sequence (no cache) and requires the logits at the
     sampled positions to match the incremental ones (the model's cache consistency),
  4. optionally compares a token file with the trace.

The grammar (which ids are legal/forced) is taken from the trace: that is the C++ grammar's job,
checked by its own tests; this script checks everything between the grammar and the ids.
Exit 0 = match, 1 = mismatch, 77 = onnxruntime/numpy not installed (ctest SKIP).

    reference_loop.py MODEL_DIR TRACE.json [--tokens FILE]
"""

from __future__ import annotations

import argparse
import json
import math
import sys

try:
    import numpy as np
    import onnxruntime as ort
except ImportError as e:  # pragma: no cover
    print(f"reference_loop: skipped ({e})")
    sys.exit(77)

MASK64 = (1 << 64) - 1


class SplitMix64:
    def __init__(self, seed: int):
        self.state = seed & MASK64

    def next(self) -> int:
        self.state = (self.state + 0x9E3779B97F4A7C15) & MASK64
        z = self.state
        z = ((z ^ (z >> 30)) * 0xBF58476D1CE4E5B9) & MASK64
        z = ((z ^ (z >> 27)) * 0x94D049BB133111EB) & MASK64
        return z ^ (z >> 31)

    def uniform(self) -> float:
        return (self.next() >> 11) * (1.0 / 9007199254740992.0)


def sample(logits, candidates, temperature, top_k, top_p, rng: SplitMix64) -> int:
    """The chain of engine/runtime/sampling/sampler_stages.cpp, step for step."""
    if len(candidates) == 1:
        return candidates[0]
    if temperature <= 0:
        best = candidates[0]
        for i in candidates:
            if logits[i] > logits[best]:
                best = i
        return best
    scored = sorted(((float(logits[i]) / temperature, i) for i in candidates), key=lambda s: (-s[0], s[1]))
    keep = len(scored)
    if 0 < top_k < keep:
        keep = top_k
    top = scored[0][0]
    probs = [math.exp(scored[i][0] - top) for i in range(keep)]
    mass = 0.0
    for p in probs:
        mass += p
    if top_p < 1.0:
        run, n = 0.0, 0
        while n < keep:
            run += probs[n]
            n += 1
            if run >= top_p * mass:
                break
        keep, mass = n, run
    u = rng.uniform() * mass
    run = 0.0
    for i in range(keep):
        run += probs[i]
        if run > u:
            return scored[i][1]
    return scored[keep - 1][1]


class Decoder:
    """The model's encoder run once on the trace's points, and decoder.onnx with its KV cache."""

    def __init__(self, model: str, meta: dict, points):
        d = meta["dims"]
        so = ort.SessionOptions()
        so.intra_op_num_threads = 1
        enc = ort.InferenceSession(f"{model}/{meta['files']['encoder']}", so, providers=["CPUExecutionProvider"])
        self.dec = ort.InferenceSession(f"{model}/{meta['files']['decoder']}", so, providers=["CPUExecutionProvider"])
        cross = enc.run(None, {"points": np.asarray(points, dtype=np.float32).reshape(1, -1, 6)})[0]  # [L, 2, H, M, D]
        self.kv_names = [f"{kv}_{l}" for l in range(d["n_layers"]) for kv in ("key", "value")]
        self.cross_feeds = {
            f"cross_{name}": np.ascontiguousarray(cross[i // 2, i % 2][None]) for i, name in enumerate(self.kv_names)
        }
        empty = np.zeros((1, d["n_heads"], 0, d["head_dim"]), np.float32)
        self.empty = [empty] * len(self.kv_names)

    def run(self, ids_, first, past_):
        """decoder.onnx on ids_ at positions first..; returns (logits, the grown per-layer cache)."""
        n = len(ids_)
        feeds = {
            "input_ids": np.asarray([ids_], np.int64),
            "positions": np.arange(first, first + n, dtype=np.int64)[None, :],
            "seqlens_k": np.asarray([first + n - 1], np.int32),
            "total_sequence_length": np.asarray(first + n, np.int32),
            **self.cross_feeds,
        }
        feeds.update({f"past_{name}": past_[i] for i, name in enumerate(self.kv_names)})
        outs = self.dec.run(None, feeds)
        return outs[0], outs[1:]


def replay(trace: dict, dec: Decoder, bos: int):
    """Every sampled id of the trace drawn again from the model's logits through the reference chain:
    (ids, [(position, logits row)]) or an error message."""
    s = trace["settings"]
    past = dec.empty
    rng = SplitMix64(int(s["seed"]))
    pending = [bos]
    fed = []  # all ids fed so far, BOS first
    checked = []  # (position index in fed+pending sequence, logits row as the model gave it)
    ids = []
    for k, step in enumerate(trace["steps"]):
        if step["forced"]:
            ids.append(step["id"])
            pending.append(step["id"])
            continue
        logits, past = dec.run(pending, len(fed), past)
        fed += pending
        row = logits[0, -1]
        checked.append((len(fed) - 1, row))
        if step.get("penalties"):  # soft face guidance: the logits the chain sampled from
            row = row.copy()
            for i, amount in step["penalties"]:
                row[i] = np.float32(row[i]) - np.float32(amount)
        candidates = [i for b, e in step["legal"] for i in range(b, e)]
        got = sample(row, candidates, float(s["temperature"]), int(s["top_k"]), float(s["top_p"]), rng)
        if got != step["id"]:
            return f"reference_loop: MISMATCH at id {k}: C++ sampled {step['id']}, reference {got}"
        ids.append(got)
        pending = [got]
    return ids, checked


def worst_uncached_difference(dec: Decoder, ids, checked, bos: int, eos: int) -> float:
    """One pass over the whole sequence without a cache: the largest logit difference to the cached rows."""
    full = [bos] + ids[:-1] if ids and ids[-1] == eos else [bos] + ids
    full = full[: max(p for p, _ in checked) + 1] if checked else full
    logits, _ = dec.run(full, 0, dec.empty)
    worst = 0.0
    for p, row in checked:
        worst = max(worst, float(np.abs(logits[0, p] - row).max()))
    return worst


def main() -> int:
    ap = argparse.ArgumentParser()
    ap.add_argument("model")
    ap.add_argument("trace")
    ap.add_argument("--tokens")
    ap.add_argument("--logit-tol", type=float, default=1e-4)
    a = ap.parse_args()

    meta = json.load(open(f"{a.model}/model.json"))
    trace = json.load(open(a.trace))
    s = trace["settings"]
    if s.get("unconstrained"):
        print("reference_loop: unconstrained traces are not checked")
        return 1
    if float(s.get("top_p_temperature", 0)) > 0:
        print("reference_loop: the official top-p chain (top_p_temperature > 0) is not reproduced here")
        return 1
    bos, eos = meta["vocab"]["bos_id"], meta["vocab"]["eos_id"]
    dec = Decoder(a.model, meta, trace["points"])
    replayed = replay(trace, dec, bos)
    if isinstance(replayed, str):
        print(replayed)
        return 1
    ids, checked = replayed
    if ids != trace["tokens"]:
        print("reference_loop: trace steps and trace tokens differ")
        return 1
    worst = worst_uncached_difference(dec, ids, checked, bos, eos)
    if worst > a.logit_tol:
        print(f"reference_loop: cached and uncached logits differ by {worst:.3g} (> {a.logit_tol})")
        return 1
    if a.tokens and [int(x) for x in open(a.tokens).read().split()] != ids:
        print("reference_loop: token file differs from the trace")
        return 1
    forced = sum(1 for st in trace["steps"] if st["forced"])
    print(
        f"reference_loop: OK: {len(ids)} ids ({forced} forced, {len(checked)} sampled) reproduced; "
        f"cached vs uncached logits within {worst:.2g}"
    )
    return 0


if __name__ == "__main__":
    sys.exit(main())
