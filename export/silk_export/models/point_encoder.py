# SPDX-License-Identifier: MIT
"""Perceiver-style point-cloud encoder: learned latent queries cross-attend to Fourier-embedded
points + normals, then self-attention over the latents. Trained jointly with the decoder."""

from __future__ import annotations

import math

import torch
from torch import nn

from .configs import ModelConfig
from .layers import LatentBlock


class FourierEmbed(nn.Module):
    """[B,N,6] (xyz, normal) -> [B,N,d]: xyz, sin/cos(2^k·π·xyz) for k < F, normal, then linear."""

    def __init__(self, n_freqs: int, d_model: int):
        super().__init__()
        self.register_buffer("freqs", (2.0 ** torch.arange(n_freqs)) * math.pi, persistent=False)
        self.proj = nn.Linear(3 + 3 * 2 * n_freqs + 3, d_model)

    def forward(self, points: torch.Tensor) -> torch.Tensor:
        xyz, nrm = points[..., :3], points[..., 3:6]
        ang = (xyz.unsqueeze(-1) * self.freqs).flatten(-2)  # [B,N,3F]
        return self.proj(torch.cat([xyz, torch.sin(ang), torch.cos(ang), nrm], dim=-1))


class PointEncoder(nn.Module):
    def __init__(self, cfg: ModelConfig):
        super().__init__()
        self.embed = FourierEmbed(cfg.fourier_freqs, cfg.d_model)
        self.latents = nn.Parameter(torch.randn(cfg.n_latents, cfg.d_model) * 0.02)
        self.cross = LatentBlock(cfg.d_model, cfg.n_heads, cfg.ff_mult)
        self.blocks = nn.ModuleList(
            LatentBlock(cfg.d_model, cfg.n_heads, cfg.ff_mult) for _ in range(cfg.encoder_layers)
        )
        self.norm = nn.LayerNorm(cfg.d_model)

    def forward(self, points: torch.Tensor) -> torch.Tensor:
        """points [B,N,6] -> latents [B,M,d]."""
        feats = self.embed(points)
        lat = self.latents.unsqueeze(0).expand(points.shape[0], -1, -1)
        lat = self.cross(lat, feats)
        for blk in self.blocks:
            lat = blk(lat)
        return self.norm(lat)
