"""The architecture registry: one entry per network family that can sit behind the model contract
(docs/model_contract.md). Everything that differs between families is here; the ONNX graphs
(onnx_graphs.py) and the exporter reach a model only through the interface below.

A model class of an architecture provides: `cfg` (ModelConfig), `bos_id`, `encode_points(points)`
-> per layer (K, V) [B,H,M,D], `embed(ids, positions)` in contract conventions,
`layers[l].self_qkv(y)` and `layers[l].block(x, cross_k, cross_v, self_attention, fused)`,
`logits(x)`, and `forward(input_ids, points, labels=None)` for teacher forcing."""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import Callable

from torch import nn

from .configs import ModelConfig


@dataclass(frozen=True)
class Architecture:
    name: str
    model_class: Callable[[ModelConfig], nn.Module]
    model_version: int  # model.json version its exports write
    preprocessing: Callable[[ModelConfig], dict]  # model.json "preprocessing" (v3)
    sampling: dict = field(default_factory=dict)  # model.json "sampling" defaults (v3)


def _silk_model(cfg: ModelConfig) -> nn.Module:
    from .silk_model import SilkModel
    return SilkModel(cfg)


def _official_model(cfg: ModelConfig) -> nn.Module:
    from ..official.model import OfficialModel
    return OfficialModel(cfg)


def _silk_preprocessing(cfg: ModelConfig) -> dict:
    return {"kind": "silk", "normalize_bound": 0.95, "merge_distance_fraction": 0.0, "surface_samples": 0,
            "round_float16": False, "n_points": cfg.n_points}


def _official_preprocessing(cfg: ModelConfig) -> dict:
    """official_network.md §4: the official inference pre-processing."""
    return {"kind": "official", "normalize_bound": 0.95, "merge_distance_fraction": 0.01,
            "surface_samples": 50000, "round_float16": True, "n_points": cfg.n_points}


ARCHITECTURES = {
    "silk": Architecture("silk", _silk_model, 2, _silk_preprocessing),
    "official": Architecture("official", _official_model, 3, _official_preprocessing,
                             {"temperature": 0.5, "top_k": 50, "top_p": 0.95, "top_p_temperature": 1.0}),
}


def get_architecture(name: str) -> Architecture:
    try:
        return ARCHITECTURES[name]
    except KeyError:
        raise ValueError(f"unknown architecture '{name}' (known: {', '.join(ARCHITECTURES)})") from None


def build_model(cfg: ModelConfig) -> nn.Module:
    return get_architecture(cfg.arch).model_class(cfg)
