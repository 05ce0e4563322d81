# SPDX-License-Identifier: MIT
"""The architecture registry: one entry per network family that can sit behind the model contract
(docs/model_contract.md), each an implementation of the Architecture interface (models/architecture.py).
A ModelConfig's `arch` names its entry; checkpoints, training and the exporter build models here."""

from __future__ import annotations

from .models.architecture import Architecture
from .models.configs import ModelConfig
from .models.silk_model import SilkModel
from .official.model import OfficialModel

ARCHITECTURES: dict[str, type[Architecture]] = {cls.name: cls for cls in (SilkModel, OfficialModel)}


def get_architecture(name: str) -> type[Architecture]:
    try:
        return ARCHITECTURES[name]
    except KeyError:
        raise ValueError(f"unknown architecture '{name}' (known: {', '.join(ARCHITECTURES)})") from None


def build_model(cfg: ModelConfig) -> Architecture:
    return get_architecture(cfg.arch).build(cfg)
