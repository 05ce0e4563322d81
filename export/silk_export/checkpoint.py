"""Checkpoints: model + optimizer + step + RNG states, written atomically so an interrupted run
resumes exactly where the last checkpoint left it."""
from __future__ import annotations

import os
from pathlib import Path

import torch

from .architectures import build_model
from .configs import config_from_dict


def save_checkpoint(path: Path, model, optimizer, step: int, extra: dict) -> None:
    path = Path(path)
    tmp = path.with_suffix(path.suffix + ".tmp")
    torch.save({"config": model.cfg.to_dict(), "model": model.state_dict(),
                "optimizer": optimizer.state_dict() if optimizer is not None else None,
                "step": step, **extra}, tmp)
    os.replace(tmp, path)


def load_checkpoint(path: Path, map_location="cpu") -> dict:
    return torch.load(path, map_location=map_location, weights_only=False)


def model_from_checkpoint(path: Path):
    ck = load_checkpoint(path)
    model = build_model(config_from_dict(ck["config"]))
    model.load_state_dict(ck["model"])
    return model.eval(), ck
