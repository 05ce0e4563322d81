# SPDX-License-Identifier: MIT
"""`silk-export loss`: token-mean cross-entropy (nats/token, tokens + EOS) of a checkpoint on the
meshes of one split, without augmentation and with fixed point samples — the held-out figure
for the model card — next to a context-free baseline: the cross-entropy of the train split's
unigram token frequencies on the same tokens, and the conditioning gap: how much worse the same
tokens score when each mesh is given another mesh's points (zero for a model that ignores its
input)."""

from __future__ import annotations

import dataclasses
import math
import time
from pathlib import Path

import numpy as np
import torch

import silk_mesh
from ..data.dataset_index import read_index
from ..checkpoint import model_from_checkpoint
from ..training.train import fixed_val_samples, evaluate_loss, select_rows


def unigram_baseline(root: Path, rows: list[dict], eval_tokens: np.ndarray, n_ids: int, eos_id: int) -> float:
    """Cross-entropy (nats/token) of add-½-smoothed unigram frequencies of `rows` on eval_tokens."""
    counts = np.full(n_ids, 0.5)
    for r in rows:
        t = np.asarray(silk_mesh.encode(silk_mesh.load_arrays(Path(root) / r["file"])), dtype=np.int32)
        np.add.at(counts, t, 1)
        counts[eos_id] += 1
    return float(-np.log(counts[eval_tokens] / counts.sum()).mean())


def other_points(samples: list) -> list:
    """The samples with each mesh's points replaced by the next mesh's (cyclically), tokens kept."""
    return [dataclasses.replace(s, points=samples[(i + 1) % len(samples)].points) for i, s in enumerate(samples)]


def split_loss(
    checkpoint: Path,
    index: Path,
    root: Path,
    split: str,
    limit: int = 0,
    seed: int = 0,
    threads: int = 1,
    baseline_split: str | None = "train",
    conditioning: bool = True,
) -> dict:
    if threads:
        torch.set_num_threads(threads)
    model, ck = model_from_checkpoint(checkpoint)
    all_rows = read_index(index)
    rows = select_rows(all_rows, split, model.cfg)
    if limit and len(rows) > limit:
        rows = [rows[i] for i in np.linspace(0, len(rows) - 1, limit).round().astype(int)]
    t0 = time.time()
    samples = fixed_val_samples(root, rows, model.cfg, len(rows), seed)
    loss = evaluate_loss(model, samples, "cpu")
    out = {
        "split": split,
        "checkpoint_step": ck["step"],
        "meshes": len(samples),
        "tokens": int(sum(s.tokens.size + 1 for s in samples)),
        "loss": loss,
        "bits_per_token": loss / math.log(2),
        "perplexity": math.exp(loss),
        "seconds": round(time.time() - t0, 1),
    }
    if conditioning and len(samples) >= 2:
        out["loss_other_points"] = evaluate_loss(model, other_points(samples), "cpu")
        out["conditioning_gap"] = out["loss_other_points"] - loss
    if baseline_split:
        eval_tokens = np.concatenate([np.append(s.tokens, model.eos_id) for s in samples])
        out["unigram_baseline"] = unigram_baseline(
            root, select_rows(all_rows, baseline_split, model.cfg), eval_tokens, model.n_logits, model.eos_id
        )
        out["baseline_split"] = baseline_split
    return out
