"""Checkpoints: model + optimizer + step + RNG states, written atomically so an interrupted run
resumes exactly where the last checkpoint left it."""
from __future__ import annotations

import os
from pathlib import Path

import torch

from .architectures import build_model
from .configs import config_from_dict


def save_state(path: Path, config: dict, model_state: dict, optim_state: dict | None, step: int,
               extra: dict) -> None:
    """Writes a checkpoint from state dicts (training gathers them from DDP/FSDP first)."""
    path = Path(path)
    tmp = path.with_suffix(path.suffix + ".tmp")
    torch.save({"config": config, "model": model_state, "optimizer": optim_state, "step": step, **extra}, tmp)
    os.replace(tmp, path)


def load_checkpoint(path: Path, map_location="cpu") -> dict:
    return torch.load(path, map_location=map_location, weights_only=False)


def model_from_checkpoint(path: Path):
    ck = load_checkpoint(path)
    model = build_model(config_from_dict(ck["config"]))
    model.load_state_dict(ck["model"])
    return model.eval(), ck
