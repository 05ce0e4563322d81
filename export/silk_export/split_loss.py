"""`silk-export loss`: token-mean cross-entropy (nats/token, tokens + EOS) of a checkpoint on the
meshes of one split, without augmentation and with fixed point samples — the held-out figure
for the model card."""
from __future__ import annotations

import math
import time
from pathlib import Path

import numpy as np
import torch

from .checkpoint import model_from_checkpoint
from .dataset_index import read_index
from .train import fixed_val_samples, evaluate_loss, select_rows


def split_loss(checkpoint: Path, index: Path, root: Path, split: str, limit: int = 0, seed: int = 0,
               threads: int = 1) -> dict:
    if threads:
        torch.set_num_threads(threads)
    model, ck = model_from_checkpoint(checkpoint)
    rows = select_rows(read_index(index), split, model.cfg)
    if limit and len(rows) > limit:
        rows = [rows[i] for i in np.linspace(0, len(rows) - 1, limit).round().astype(int)]
    t0 = time.time()
    samples = fixed_val_samples(root, rows, model.cfg, len(rows), seed)
    loss = evaluate_loss(model, samples, "cpu")
    return {"split": split, "checkpoint_step": ck["step"], "meshes": len(samples),
            "tokens": int(sum(s.tokens.size + 1 for s in samples)), "loss": loss,
            "bits_per_token": loss / math.log(2), "perplexity": math.exp(loss),
            "seconds": round(time.time() - t0, 1)}
