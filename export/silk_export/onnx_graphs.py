"""The two graphs of docs/model_contract.md as thin nn.Modules over SilkModel: batch 1,
time-major self-attention K/V [P, L, 2, H, D], per-layer cross K/V [L, 2, H, M, D]."""
from __future__ import annotations

import torch
from torch import nn

from .model import SilkModel


class EncoderGraph(nn.Module):
    """points [1,N,6] -> cross_kv [L,2,H,M,D]."""

    def __init__(self, model: SilkModel):
        super().__init__()
        self.model = model

    def forward(self, points: torch.Tensor) -> torch.Tensor:
        kv = self.model.encode_points(points)
        return torch.stack([torch.stack([k[0], v[0]], dim=0) for k, v in kv], dim=0)


def split_past(past_kv: torch.Tensor, n_layers: int) -> list[tuple[torch.Tensor, torch.Tensor]]:
    """[P,L,2,H,D] -> per layer (K, V) [1,H,P,D]."""
    return [(past_kv[:, l, 0].permute(1, 0, 2).unsqueeze(0), past_kv[:, l, 1].permute(1, 0, 2).unsqueeze(0))
            for l in range(n_layers)]


def join_new(new: list[tuple[torch.Tensor, torch.Tensor]]) -> torch.Tensor:
    """per layer (K, V) [1,H,T,D] -> [T,L,2,H,D]."""
    return torch.stack([torch.stack([k[0].permute(1, 0, 2), v[0].permute(1, 0, 2)], dim=1) for k, v in new], dim=1)


class DecoderGraph(nn.Module):
    """(input_ids [1,T], positions [1,T], past_kv [P,L,2,H,D], cross_kv [L,2,H,M,D])
    -> (logits [1,T,10269], new_kv [T,L,2,H,D])."""

    def __init__(self, model: SilkModel):
        super().__init__()
        self.model = model

    def forward(self, input_ids, positions, past_kv, cross_kv):
        n = self.model.cfg.n_layers
        cross = [(cross_kv[l, 0].unsqueeze(0), cross_kv[l, 1].unsqueeze(0)) for l in range(n)]
        logits, new = self.model.step(input_ids, positions, split_past(past_kv, n), cross, fused=False)
        return logits, join_new(new)
