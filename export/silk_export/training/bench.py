# SPDX-License-Identifier: MIT
"""`silk-export bench`: training throughput (tokens/s, forward + backward + AdamW step) per model
config on synthetic sequences of one length, to size training runs on a given machine."""

from __future__ import annotations

import platform
import time

import torch

from ..models.configs import get_config
from ..models.silk_model import SilkModel
from ..vocab import load_vocab


def bench_config(name: str, steps: int, seq_len: int, batch_size: int, seed: int) -> dict:
    torch.manual_seed(seed)
    cfg = get_config(name)
    vocab = load_vocab()
    model = SilkModel(cfg).train()
    opt = torch.optim.AdamW(model.parameters(), lr=1e-4, betas=(0.9, 0.99))
    s = min(seq_len, cfg.max_seq_len - 1)
    ids = torch.randint(0, vocab.format_vocab_size, (batch_size, s))
    ids[:, 0] = vocab.bos_id
    labels = torch.roll(ids, -1, dims=1)
    labels[:, -1] = vocab.eos_id
    points = torch.randn(batch_size, cfg.n_points, 6)
    times = []
    for i in range(steps + 1):  # the first step warms up and is not timed
        t0 = time.perf_counter()
        loss, _ = model(ids, points, labels)
        opt.zero_grad(set_to_none=True)
        loss.backward()
        opt.step()
        if i:
            times.append(time.perf_counter() - t0)
    per_step = sum(times) / len(times)
    return {
        "config": name,
        "parameters": model.num_parameters(),
        "seq_len": s,
        "batch_size": batch_size,
        "steps_timed": len(times),
        "seconds_per_step": round(per_step, 3),
        "tokens_per_s": round(batch_size * s / per_step, 1),
    }


def bench_configs(names, steps=3, seq_len=1024, batch_size=1, threads=0, seed=0) -> dict:
    if threads:
        torch.set_num_threads(threads)
    return {
        "machine": {
            "cpu": platform.processor() or platform.machine(),
            "threads": torch.get_num_threads(),
            "torch": torch.__version__,
            "device": "cpu",
        },
        "results": [bench_config(n, steps, seq_len, batch_size, seed) for n in names],
    }
