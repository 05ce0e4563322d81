# SPDX-License-Identifier: MIT
"""The two graphs of docs/model_contract.md as thin nn.Modules over a model of any registered
architecture (silk_export.models.architecture).
The decoder's self-attention is onnxruntime's GroupQueryAttention over one head-major cache per
layer and K/V, so the runtime can share past_* and present_* and nothing is copied per step."""

from __future__ import annotations

import torch
from torch import nn

from ..models.layers import attend, merge_heads, split_heads


class EncoderGraph(nn.Module):
    """points [1,N,6] -> cross_kv [L,2,H,M,D]."""

    def __init__(self, model: nn.Module):
        super().__init__()
        self.model = model

    def forward(self, points: torch.Tensor) -> torch.Tensor:
        kv = self.model.encode_points(points)
        return torch.stack([torch.stack([k[0], v[0]], dim=0) for k, v in kv], dim=0)


def decoder_input_names(n_layers: int) -> list[str]:
    names = ["input_ids", "positions", "seqlens_k", "total_sequence_length"]
    names += [f"past_{kv}_{l}" for l in range(n_layers) for kv in ("key", "value")]
    names += [f"cross_{kv}_{l}" for l in range(n_layers) for kv in ("key", "value")]
    return names


def decoder_output_names(n_layers: int) -> list[str]:
    return ["logits"] + [f"present_{kv}_{l}" for l in range(n_layers) for kv in ("key", "value")]


class GroupQueryAttention(torch.autograd.Function):
    """Exported as com.microsoft GroupQueryAttention (num_heads = kv_num_heads = H, scale
    1/sqrt(D) unless `scale` is given, no rotary). The eager forward, run only while tracing, is
    the same computation for an unshared cache: past [1,H,P,D] holds positions 0..P-1 and present = past + new."""

    @staticmethod
    def forward(ctx, q, k, v, past_k, past_v, seqlens_k, total, n_heads: int, scale: float = 0.0):
        k_all = torch.cat([past_k, split_heads(k, n_heads)], dim=2)
        v_all = torch.cat([past_v, split_heads(v, n_heads)], dim=2)
        t, p = q.shape[1], past_k.shape[2]
        allowed = torch.ones(t, p + t, dtype=torch.bool).tril(diagonal=p)
        a = attend(split_heads(q, n_heads), k_all, v_all, allowed=allowed, fused=False, scale=scale or None)
        return merge_heads(a), k_all, v_all

    @staticmethod
    def symbolic(g, q, k, v, past_k, past_v, seqlens_k, total, n_heads: int, scale: float = 0.0):
        attrs = {"num_heads_i": n_heads, "kv_num_heads_i": n_heads}
        if scale:  # 0: onnxruntime's default 1/sqrt(D)
            attrs["scale_f"] = scale
        out, present_k, present_v = g.op(
            "com.microsoft::GroupQueryAttention", q, k, v, past_k, past_v, seqlens_k, total, outputs=3, **attrs
        )
        out.setType(q.type())  # onnx has no shape inference for the contrib op: state the shapes
        present_k.setType(past_k.type())
        present_v.setType(past_v.type())
        return out, present_k, present_v


class DecoderGraph(nn.Module):
    """(input_ids [1,T], positions [1,T], seqlens_k [1] = P+T-1, total_sequence_length [] = P+T,
    past_key_l / past_value_l [1,H,C,D], cross_key_l / cross_value_l [1,H,M,D])
    -> (logits [1,T,10269], present_key_l / present_value_l [1,H,C',D]).

    With C >= P+T and present bound to the past buffer, the new rows land at P..P+T-1 in place
    (C' = C); with past of exactly P rows and present left to onnxruntime, C' = P+T.

    The model is reached through the architecture interface (silk_export.models.architecture):
    model.embed(ids, positions), model.layers[l].self_qkv(y) and .block(...), model.logits(x),
    and cfg.qk_scale (0 = 1/sqrt(D))."""

    def __init__(self, model: nn.Module):
        super().__init__()
        self.model = model

    def forward(self, input_ids, positions, seqlens_k, total_sequence_length, *caches):
        m = self.model
        n, h, scale = m.cfg.n_layers, m.cfg.n_heads, m.cfg.qk_scale
        past, cross = caches[: 2 * n], caches[2 * n :]
        x = m.embed(input_ids, positions)
        present = []
        for l, layer in enumerate(m.layers):

            def self_attention(y, layer=layer, l=l):
                a, k_all, v_all = GroupQueryAttention.apply(
                    *layer.self_qkv(y), past[2 * l], past[2 * l + 1], seqlens_k, total_sequence_length, h, scale
                )
                return a, (k_all, v_all)

            x, kv = layer.block(x, cross[2 * l], cross[2 * l + 1], self_attention, fused=False)
            present += list(kv)
        return (m.logits(x), *present)
