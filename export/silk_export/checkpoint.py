# SPDX-License-Identifier: MIT
"""Checkpoints: model + optimizer + step + RNG states, written atomically so an interrupted run
resumes exactly where the last checkpoint left it."""

from __future__ import annotations

import os
from pathlib import Path

import torch

from .models.configs import config_from_dict
from .registry import build_model


def save_state(path: Path, config: dict, model_state: dict, optim_state: dict | None, step: int, extra: dict) -> None:
    """Writes a checkpoint from state dicts (training gathers them from DDP/FSDP first)."""
    path = Path(path)
    tmp = path.with_suffix(path.suffix + ".tmp")
    torch.save({"config": config, "model": model_state, "optimizer": optim_state, "step": step, **extra}, tmp)
    os.replace(tmp, path)


def load_checkpoint(path: Path, map_location="cpu") -> dict:
    """A checkpoint written by save_state or pack_checkpoint. A packed one's bf16 optimizer moments
    need no conversion here: torch's Optimizer.load_state_dict casts them to the parameters' dtype."""
    return torch.load(path, map_location=map_location, weights_only=False)


def pack_checkpoint(src: Path, dst: Path, max_bytes: int = 40_000_000) -> dict:
    """Writes a smaller copy of a training checkpoint that still resumes: the optimizer's moment
    tensors (AdamW exp_avg / exp_avg_sq, two thirds of the bytes) in bfloat16, everything else as
    is. Resuming from it continues the same run (same step, sample stream and schedule); only the
    moments lose precision (relative 2^-8). Used for the one resumable checkpoint kept in the
    repository (scripts/train_default_model.sh), which must stay under `max_bytes`."""
    ck = load_checkpoint(src)
    packed = 0
    for state in (ck.get("optimizer") or {}).get("state", {}).values():
        for k, v in state.items():
            if torch.is_tensor(v) and v.is_floating_point() and v.dim() > 0 and v.dtype != torch.bfloat16:
                state[k] = v.to(torch.bfloat16)
                packed += 1
    ck["packed"] = {"optimizer_moments": "bfloat16", "tensors": packed, "from": Path(src).name}
    dst = Path(dst)
    tmp = dst.with_suffix(dst.suffix + ".tmp")
    torch.save(ck, tmp)
    size = tmp.stat().st_size
    if max_bytes and size > max_bytes:
        tmp.unlink()
        raise ValueError(f"{dst}: the packed checkpoint has {size:,} bytes, over the {max_bytes:,}-byte limit")
    os.replace(tmp, dst)
    return {"step": ck.get("step"), "bytes": size, "packed_tensors": packed}


def model_from_checkpoint(path: Path):
    ck = load_checkpoint(path)
    model = build_model(config_from_dict(ck["config"]))
    model.load_state_dict(ck["model"])
    return model.eval(), ck
