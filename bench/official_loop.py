#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""official_loop: the official PyTorch generation loop's cost per model call at given depths, for
bench/time_to_mesh (which runs it in the same run and extrapolates by the measured cost per depth).

What runs: silk_export's PyTorch model of the released network (silk_export/official/model.py,
the official architecture and state_dict layout; parity with the official code is tested on the
shared fixture) at the release size with random weights, float32 on the CPU, torch.no_grad,
batch 1, `--threads` intra-op threads: for each depth d, the prefix (BOS + d-1 random ids) is
prefilled in one call, then `--steps` single-id calls are timed, each `Architecture.step` with the
self K/V cache grown by torch.cat per call, as the official `generate` does (x-transformers'
cache, `cache_kv=True`, one id per call). The official code runs the model in half precision on
CUDA; on a CPU float32 is what runs (half matmuls there are far slower), as in the figures the
issue quotes. Sampling (top-k on 10,269 logits) is left out: it is not the model's cost.
Two untimed calls per depth come first. Needs an idle machine: with other processes on the cores
PyTorch's OpenMP threads spin against them and a call takes several times longer (measured
2026-12-04 at load 10 on 2 cores: 4.1 s per call, against 0.17-0.32 s with 1 thread minutes later).

    python3 bench/official_loop.py [--depths 0 1024] [--steps 24] [--threads 2]   # prints JSON
"""

from __future__ import annotations

import argparse
import json
import sys
import time
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPO / "export"))

import torch  # noqa: E402


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--depths", nargs="+", type=int, default=[0, 1024])
    ap.add_argument("--steps", type=int, default=24)
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--seed", type=int, default=0)
    a = ap.parse_args()
    torch.set_num_threads(a.threads)
    from silk_export.official.checkpoint import RELEASE_SIZES, official_config
    from silk_export.official.model import OfficialModel

    t0 = time.perf_counter()
    model = OfficialModel(official_config(RELEASE_SIZES, {})).init_random(seed=a.seed).float().eval()
    build_s = time.perf_counter() - t0
    cfg = model.cfg
    gen = torch.Generator().manual_seed(a.seed)
    out = {
        "what": "silk_export OfficialModel (release size, random weights), float32, CPU, step + torch.cat cache",
        "threads": a.threads,
        "steps": a.steps,
        "build_seconds": round(build_s, 1),
        "ms_per_call": {},
    }
    with torch.no_grad():
        points = torch.rand(1, cfg.n_points, 6, generator=gen) * 1.8 - 0.9
        t0 = time.perf_counter()
        cross = model.encode_points(points)
        out["encoder_seconds"] = round(time.perf_counter() - t0, 2)
        for depth in a.depths:
            past = model.empty_cache()
            if depth > 0:
                ids = torch.randint(0, model.eos_id, (1, depth), generator=gen)
                ids[0, 0] = model.bos_id
                _, past = model.step(ids, torch.arange(depth).unsqueeze(0), past, cross)
            pos = depth
            for _ in range(2):  # untimed warm-up calls (first-call allocations); their K/V are dropped
                ids = torch.tensor([[model.bos_id if pos == 0 else 5]])
                model.step(ids, torch.tensor([[pos]]), past, cross)
            t0 = time.perf_counter()
            for _ in range(a.steps):
                ids = torch.randint(0, model.eos_id, (1, 1), generator=gen) if pos else torch.tensor([[model.bos_id]])
                _, new = model.step(ids, torch.tensor([[pos]]), past, cross)
                past = [(torch.cat([pk, kn], 2), torch.cat([pv, vn], 2)) for (pk, pv), (kn, vn) in zip(past, new)]
                pos += 1
            out["ms_per_call"][str(depth)] = round(1000 * (time.perf_counter() - t0) / a.steps, 2)
    print(json.dumps(out))
    return 0


if __name__ == "__main__":
    sys.exit(main())
