# SPDX-License-Identifier: MIT
"""The interface every network family behind the model contract (docs/model_contract.md)
implements, so training, the ONNX graphs, the exporter, PyTorch generation and the model card
reach a model only through it. The registered families are in silk_export/registry.py.

An architecture is an nn.Module subclass of `Architecture` that provides

* building: `build(cfg)` (the constructor by default) from a ModelConfig, and `cfg`, `bos_id`,
  `eos_id`, `pad_id`, `n_logits`;
* the forward pass: `forward(input_ids, points, labels=None)`, teacher forcing;
* its decoder as the pieces the ONNX decoder graph and `step` assemble: `encode_points(points)`
  -> per layer (K, V) [B,H,M,D], `embed(ids, positions)` in contract conventions,
  `layers[l].self_qkv(y)` and `layers[l].block(x, cross_k, cross_v, self_attention, fused)`,
  `logits(x)`, and the attention score scale `cfg.qk_scale` (0: 1/sqrt(D));
* one incremental decoding step with a KV cache: `step(...)`, written here once over those
  pieces, so every architecture decodes in PyTorch the way its exported decoder does;
* its point-cloud pre-processing: `preprocessing(cfg)`, model.json "preprocessing" (libsilk
  reads it; "kind" also picks what training and PyTorch generation feed the encoder);
* what its exports and model card say: `name`, `model_version` (the model.json version its
  exports write), `sampling` (model.json "sampling" defaults) and `card_summary()`."""

from __future__ import annotations

from abc import ABC, abstractmethod
from typing import ClassVar

import torch
from torch import nn

from .configs import ModelConfig
from .layers import attend, merge_heads, split_heads

IGNORE_INDEX = -100  # label of a position no loss scores (collate pads with it)

KVCache = list[tuple[torch.Tensor, torch.Tensor]]  # per layer (K, V) [B,H,P,D]


class Architecture(nn.Module, ABC):
    name: ClassVar[str]
    model_version: ClassVar[int]  # model.json version its exports write
    sampling: ClassVar[dict] = {}  # model.json "sampling" defaults (contract v3); {} = libsilk's

    cfg: ModelConfig
    bos_id: int
    eos_id: int
    pad_id: int
    n_logits: int
    layers: nn.ModuleList

    @classmethod
    def build(cls, cfg: ModelConfig) -> "Architecture":
        """A freshly initialised network of this architecture for `cfg`."""
        return cls(cfg)

    @classmethod
    @abstractmethod
    def preprocessing(cls, cfg: ModelConfig) -> dict:
        """model.json "preprocessing": how libsilk turns a mesh into the encoder's points."""

    @classmethod
    def points_kind(cls, cfg: ModelConfig) -> str:
        """The libsilk pre-processing ("silk" or "official") the encoder expects its points from."""
        return cls.preprocessing(cfg)["kind"]

    @classmethod
    @abstractmethod
    def card_summary(cls) -> list[str]:
        """What a model card says the network is: the opening of its "What it is" section
        (markdown lines)."""

    @abstractmethod
    def forward(self, input_ids: torch.Tensor, points: torch.Tensor, labels: torch.Tensor | None = None):
        """Teacher forcing. input_ids [B,S] start with BOS (PAD after the end), contract positions
        0..S-1. Returns logits [B,S,n_logits], or (loss, logits) with labels (IGNORE_INDEX = not
        scored)."""

    @abstractmethod
    def encode_points(self, points: torch.Tensor) -> KVCache:
        """points [B,N,6] -> per decoder layer the cross-attention (K, V) [B,H,M,D]."""

    @abstractmethod
    def embed(self, ids: torch.Tensor, positions: torch.Tensor) -> torch.Tensor:
        """Contract ids and positions [B,T] -> decoder input rows [B,T,d_model]."""

    @abstractmethod
    def logits(self, x: torch.Tensor) -> torch.Tensor:
        """Last decoder layer's output [B,T,d_model] -> logits [B,T,n_logits]."""

    def empty_cache(self, batch: int = 1) -> KVCache:
        """A self-attention KV cache holding no position yet."""
        empty = torch.zeros(batch, self.cfg.n_heads, 0, self.cfg.head_dim)
        return [(empty, empty) for _ in range(self.cfg.n_layers)]

    def step(
        self, input_ids: torch.Tensor, positions: torch.Tensor, past: KVCache, cross: KVCache, fused: bool = False
    ) -> tuple[torch.Tensor, KVCache]:
        """Incremental decoding with a KV cache, the batch-1 layout of the ONNX decoder.

        input_ids, positions [1,T]; past: per layer (K, V) [1,H,P,D] (P may be 0) holding positions
        0..P-1; cross: encode_points' output. Key j is visible to a new token iff j <= its position.
        Returns (logits [1,T,n_logits], per layer the new (K, V) [1,H,T,D] to append to past)."""
        x = self.embed(input_ids, positions)
        new_index = positions[0]
        key_index = torch.cat([torch.arange(past[0][0].shape[2], device=new_index.device), new_index])
        allowed = key_index.unsqueeze(0) <= new_index.unsqueeze(1)  # [T, P+T]
        h, scale = self.cfg.n_heads, self.cfg.qk_scale or None
        new = []
        for layer, (pk, pv), (ck, cv) in zip(self.layers, past, cross):

            def self_attention(y, pk=pk, pv=pv, layer=layer):
                q, k, v = (split_heads(t, h) for t in layer.self_qkv(y))
                a = attend(
                    q, torch.cat([pk, k], dim=2), torch.cat([pv, v], dim=2), allowed=allowed, fused=fused, scale=scale
                )
                return merge_heads(a), (k, v)

            x, kv = layer.block(x, ck, cv, self_attention, fused)
            new.append(kv)
        return self.logits(x), new

    def num_parameters(self) -> int:
        return sum(p.numel() for p in self.parameters())
