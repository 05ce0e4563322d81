# SPDX-License-Identifier: MIT
"""Transformer building blocks shared by the point encoder and the decoder: multi-head
attention (fused SDPA for training, plain MatMul/Softmax for ONNX export) and the MLP."""

from __future__ import annotations

import math

import torch
import torch.nn.functional as F
from torch import nn


def attend(
    q: torch.Tensor,
    k: torch.Tensor,
    v: torch.Tensor,
    causal: bool = False,
    allowed: torch.Tensor | None = None,
    fused: bool = True,
    scale: float | None = None,
) -> torch.Tensor:
    """q [B,H,T,D], k/v [B,H,S,D] -> [B,H,T,D].

    causal: query i sees keys 0..i (T == S). allowed: bool [T,S] mask (export path).
    fused=False spells the computation out with standard ops only (what goes into ONNX).
    scale: score factor (default 1/sqrt(D))."""
    if fused and allowed is None:
        return F.scaled_dot_product_attention(q, k, v, is_causal=causal, scale=scale)
    scores = torch.matmul(q, k.transpose(-1, -2)) * (scale or 1.0 / math.sqrt(q.shape[-1]))
    if causal:
        t, s = scores.shape[-2], scores.shape[-1]
        allowed = torch.ones(t, s, dtype=torch.bool, device=q.device).tril()
    if allowed is not None:
        scores = scores.masked_fill(~allowed, float("-inf"))
    return torch.matmul(torch.softmax(scores, dim=-1), v)


def split_heads(x: torch.Tensor, n_heads: int) -> torch.Tensor:
    b, t, d = x.shape
    return x.view(b, t, n_heads, d // n_heads).transpose(1, 2)


def merge_heads(x: torch.Tensor) -> torch.Tensor:
    b, h, t, d = x.shape
    return x.transpose(1, 2).reshape(b, t, h * d)


class MultiHeadAttention(nn.Module):
    """Projections for one attention; the caller decides where keys/values come from."""

    def __init__(self, d_model: int, n_heads: int, d_context: int | None = None):
        super().__init__()
        d_context = d_context or d_model
        self.n_heads = n_heads
        self.q = nn.Linear(d_model, d_model, bias=False)
        self.k = nn.Linear(d_context, d_model, bias=False)
        self.v = nn.Linear(d_context, d_model, bias=False)
        self.o = nn.Linear(d_model, d_model)

    def keys_values(self, context: torch.Tensor) -> tuple[torch.Tensor, torch.Tensor]:
        return split_heads(self.k(context), self.n_heads), split_heads(self.v(context), self.n_heads)

    def forward(self, x: torch.Tensor, context: torch.Tensor) -> torch.Tensor:
        k, v = self.keys_values(context)
        return self.o(merge_heads(attend(split_heads(self.q(x), self.n_heads), k, v, fused=False)))


class FeedForward(nn.Module):
    def __init__(self, d_model: int, mult: int = 4):
        super().__init__()
        self.net = nn.Sequential(nn.Linear(d_model, mult * d_model), nn.GELU(), nn.Linear(mult * d_model, d_model))

    def forward(self, x: torch.Tensor) -> torch.Tensor:
        return self.net(x)


class LatentBlock(nn.Module):
    """Pre-norm (cross- or self-) attention + MLP over perceiver latents."""

    def __init__(self, d_model: int, n_heads: int, ff_mult: int):
        super().__init__()
        self.norm_q = nn.LayerNorm(d_model)
        self.norm_ctx = nn.LayerNorm(d_model)
        self.attn = MultiHeadAttention(d_model, n_heads)
        self.norm_ff = nn.LayerNorm(d_model)
        self.ff = FeedForward(d_model, ff_mult)

    def forward(self, latents: torch.Tensor, context: torch.Tensor | None = None) -> torch.Tensor:
        q = self.norm_q(latents)
        ctx = q if context is None else self.norm_ctx(context)
        latents = latents + self.attn(q, ctx)
        return latents + self.ff(self.norm_ff(latents))
