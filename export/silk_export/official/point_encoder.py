# SPDX-License-Identifier: MIT
"""The released Mesh Silksong point encoder (official_network.md §3.1): Fourier features of the points,
learned queries cross-attending to them, self-attention blocks, final LayerNorm. Parameter names
follow the release checkpoint's leaves so the importer maps keys by prefix only."""

from __future__ import annotations

import torch
import torch.nn.functional as F
from torch import nn


def fourier_features(points: torch.Tensor, n_freqs: int) -> torch.Tensor:
    """[B,N,6] (xyz, normal) -> [B,N,3+6F+3]: xyz, sin(c·2^j) coordinate-major, cos(...), normal.
    No π, frequencies 2^0..2^(F-1)."""
    xyz, nrm = points[..., :3], points[..., 3:6]
    freqs = 2.0 ** torch.arange(n_freqs, dtype=points.dtype, device=points.device)
    ang = (xyz.unsqueeze(-1) * freqs).flatten(-2)
    return torch.cat([xyz, torch.sin(ang), torch.cos(ang), nrm], dim=-1)


def head_attention(q: torch.Tensor, k: torch.Tensor, v: torch.Tensor) -> torch.Tensor:
    """q [B,H,T,dh], k/v [B,H,S,dh]; unmasked softmax(q·k/sqrt(dh)) v, heads merged -> [B,T,H·dh].
    Spelled out with MatMul/Softmax so the ONNX graph holds standard ops only."""
    scores = torch.matmul(q, k.transpose(-1, -2)) * (q.shape[-1] ** -0.5)
    out = torch.matmul(torch.softmax(scores, dim=-1), v)
    b, h, t, d = out.shape
    return out.transpose(1, 2).reshape(b, t, h * d)


def packed_heads(x: torch.Tensor, n_heads: int, parts: int) -> list[torch.Tensor]:
    """Splits a per-head packed projection [B,T,H·parts·dh] (head h owns one contiguous block,
    laid out part by part) into `parts` tensors [B,H,T,dh]."""
    b, t, w = x.shape
    dh = w // (n_heads * parts)
    blocks = x.view(b, t, n_heads, parts, dh).permute(3, 0, 2, 1, 4)
    return list(blocks.unbind(0))


class Mlp(nn.Module):
    def __init__(self, width: int):
        super().__init__()
        self.c_fc = nn.Linear(width, 4 * width)
        self.c_proj = nn.Linear(4 * width, width)

    def forward(self, x: torch.Tensor) -> torch.Tensor:
        return self.c_proj(F.gelu(self.c_fc(x)))


class CrossAttention(nn.Module):
    def __init__(self, width: int, n_heads: int):
        super().__init__()
        self.n_heads = n_heads
        self.c_q = nn.Linear(width, width, bias=False)
        self.c_kv = nn.Linear(width, 2 * width, bias=False)
        self.c_proj = nn.Linear(width, width)

    def forward(self, x: torch.Tensor, data: torch.Tensor) -> torch.Tensor:
        (q,) = packed_heads(self.c_q(x), self.n_heads, 1)
        k, v = packed_heads(self.c_kv(data), self.n_heads, 2)
        return self.c_proj(head_attention(q, k, v))


class SelfAttention(nn.Module):
    def __init__(self, width: int, n_heads: int):
        super().__init__()
        self.n_heads = n_heads
        self.c_qkv = nn.Linear(width, 3 * width, bias=False)
        self.c_proj = nn.Linear(width, width)

    def forward(self, x: torch.Tensor) -> torch.Tensor:
        q, k, v = packed_heads(self.c_qkv(x), self.n_heads, 3)
        return self.c_proj(head_attention(q, k, v))


class CrossBlock(nn.Module):
    def __init__(self, width: int, n_heads: int):
        super().__init__()
        self.ln_1, self.ln_2, self.ln_3 = nn.LayerNorm(width), nn.LayerNorm(width), nn.LayerNorm(width)
        self.attn = CrossAttention(width, n_heads)
        self.mlp = Mlp(width)

    def forward(self, queries: torch.Tensor, data: torch.Tensor) -> torch.Tensor:
        x = queries + self.attn(self.ln_1(queries), self.ln_2(data))
        return x + self.mlp(self.ln_3(x))


class SelfBlock(nn.Module):
    def __init__(self, width: int, n_heads: int):
        super().__init__()
        self.ln_1, self.ln_2 = nn.LayerNorm(width), nn.LayerNorm(width)
        self.attn = SelfAttention(width, n_heads)
        self.mlp = Mlp(width)

    def forward(self, x: torch.Tensor) -> torch.Tensor:
        x = x + self.attn(self.ln_1(x))
        return x + self.mlp(self.ln_2(x))


class SelfStack(nn.Module):
    def __init__(self, width: int, n_heads: int, depth: int):
        super().__init__()
        self.resblocks = nn.ModuleList(SelfBlock(width, n_heads) for _ in range(depth))

    def forward(self, x: torch.Tensor) -> torch.Tensor:
        for block in self.resblocks:
            x = block(x)
        return x


class OfficialPointEncoder(nn.Module):
    """points [B,N,6] -> latents [B,Q,W] (Q = 257: the shape-embed row, then 256 latents)."""

    def __init__(self, width: int, n_heads: int, depth: int, n_queries: int, n_freqs: int):
        super().__init__()
        self.n_freqs = n_freqs
        self.query = nn.Parameter(torch.zeros(n_queries, width))
        self.input_proj = nn.Linear(3 + 6 * n_freqs + 3, width)
        self.cross_attn = CrossBlock(width, n_heads)
        self.self_attn = SelfStack(width, n_heads, depth)
        self.ln_post = nn.LayerNorm(width)

    def forward(self, points: torch.Tensor) -> torch.Tensor:
        data = self.input_proj(fourier_features(points, self.n_freqs))
        queries = self.query.unsqueeze(0).expand(points.shape[0], -1, -1)
        return self.ln_post(self.self_attn(self.cross_attn(queries, data)))
