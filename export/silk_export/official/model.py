# SPDX-License-Identifier: MIT
"""The released Mesh Silksong network (official_network.md §3), written from that description: point
encoder + conditioner projections, then a pre-norm decoder whose blocks run causal
self-attention and cross-attention (both with L2 qk-norm and a fixed score scale of 10; the
cross-attention prepends learned memory slots) and a GLU feed-forward.

It speaks the Silk contract's token conventions (docs/model_contract.md, arch "official"):
input id BOS (10269) is the learned `sos_token` with no position and no type vector, and a mesh
token at contract position p >= 1 uses `abs_pos_emb` row p - 1, so token i of the official
code list sits at row i as in the official implementation."""

from __future__ import annotations

import torch
import torch.nn.functional as F
from torch import nn
from torch.utils.checkpoint import checkpoint

from ..models.architecture import IGNORE_INDEX, Architecture
from ..models.configs import ModelConfig
from ..models.layers import attend, merge_heads, split_heads
from ..vocab import TYPE_CLASSES, load_vocab
from .point_encoder import OfficialPointEncoder

# The five type vectors in TYPE_CLASSES order (X, S, B, K, O), named as in the release file.
TYPE_VECTOR_NAMES = ("matrix_in0_embed", "matrix_in1_embed", "matrix_out_embed", "block_embed", "offset_embed")
L2_EPS = 1e-12


def l2_heads(x: torch.Tensor, n_heads: int) -> torch.Tensor:
    """[B,T,H·dh] with each head's dh values divided by max(their L2 norm, 1e-12)."""
    b, t, w = x.shape
    return F.normalize(x.view(b, t, n_heads, w // n_heads), dim=-1, eps=L2_EPS).reshape(b, t, w)


class Attention(nn.Module):
    """Bias-free projections of one attention (width H·dh, possibly != d_model)."""

    def __init__(self, d_model: int, n_heads: int, head_dim: int, d_context: int | None = None):
        super().__init__()
        inner = n_heads * head_dim
        self.n_heads = n_heads
        self.to_q = nn.Linear(d_model, inner, bias=False)
        self.to_k = nn.Linear(d_context or d_model, inner, bias=False)
        self.to_v = nn.Linear(d_context or d_model, inner, bias=False)
        self.to_out = nn.Linear(inner, d_model, bias=False)


class CrossAttention(Attention):
    """Cross-attention whose keys/values are [memory slots ; projected context]."""

    def __init__(self, d_model: int, n_heads: int, head_dim: int, d_context: int, slots: int):
        super().__init__(d_model, n_heads, head_dim, d_context)
        self.mem_k = nn.Parameter(torch.zeros(n_heads, slots, head_dim))
        self.mem_v = nn.Parameter(torch.zeros(n_heads, slots, head_dim))

    def keys_values(self, context: torch.Tensor) -> tuple[torch.Tensor, torch.Tensor]:
        """context [B,Q,C] -> keys (L2-normalised, memory included) and values, [B,H,slots+Q,dh]."""
        b = context.shape[0]
        k = split_heads(l2_heads(self.to_k(context), self.n_heads), self.n_heads)
        v = split_heads(self.to_v(context), self.n_heads)
        mem_k = F.normalize(self.mem_k, dim=-1, eps=L2_EPS).unsqueeze(0).expand(b, -1, -1, -1)
        mem_v = self.mem_v.unsqueeze(0).expand(b, -1, -1, -1)
        return torch.cat([mem_k, k], dim=2), torch.cat([mem_v, v], dim=2)


class GluFeedForward(nn.Module):
    def __init__(self, d_model: int, inner: int):
        super().__init__()
        self.proj_in = nn.Linear(d_model, 2 * inner)
        self.proj_out = nn.Linear(inner, d_model)

    def forward(self, x: torch.Tensor) -> torch.Tensor:
        value, gate = self.proj_in(x).chunk(2, dim=-1)
        return self.proj_out(value * F.gelu(gate))


class OfficialBlock(nn.Module):
    fsdp_forward_methods = ("cross_kv", "block")  # the entry points OfficialModel calls (training/distributed.py)

    def __init__(self, cfg: ModelConfig):
        super().__init__()
        d, h, dh = cfg.d_model, cfg.n_heads, cfg.head_dim
        self.scale = cfg.qk_scale
        self.self_norm = nn.LayerNorm(d)
        self.self_attn = Attention(d, h, dh)
        self.cross_norm = nn.LayerNorm(d)
        self.cross_attn = CrossAttention(d, h, dh, cfg.context_dim, cfg.memory_slots)
        self.ff_norm = nn.LayerNorm(d)
        self.ff = GluFeedForward(d, cfg.ff_mult * d)

    def cross_kv(self, context: torch.Tensor) -> tuple[torch.Tensor, torch.Tensor]:
        return self.cross_attn.keys_values(context)

    def self_qkv(self, y: torch.Tensor) -> tuple[torch.Tensor, torch.Tensor, torch.Tensor]:
        """Self-attention q, k (both L2-normalised per head) and v of the normed input, [B,T,H·dh]."""
        a = self.self_attn
        return l2_heads(a.to_q(y), a.n_heads), l2_heads(a.to_k(y), a.n_heads), a.to_v(y)

    def block(self, x, cross_k, cross_v, self_attention, fused=True):
        """Residual structure with the self-attention step supplied by the caller (as
        DecoderLayer.block): self_attention(normed x) -> (heads merged [B,T,H·dh], extra)."""
        a, extra = self_attention(self.self_norm(x))
        x = x + self.self_attn.to_out(a)
        c = self.cross_attn
        q = split_heads(l2_heads(c.to_q(self.cross_norm(x)), c.n_heads), c.n_heads)
        x = x + c.to_out(merge_heads(attend(q, cross_k, cross_v, fused=fused, scale=self.scale)))
        return x + self.ff(self.ff_norm(x)), extra


class OfficialModel(Architecture):
    """Architecture "official" (model.json version 3, with the official pre-processing and
    sampling defaults of official_network.md §4)."""

    name = "official"
    model_version = 3
    sampling = {"temperature": 0.5, "top_k": 50, "top_p": 0.95, "top_p_temperature": 1.0}

    @classmethod
    def preprocessing(cls, cfg: ModelConfig) -> dict:
        """official_network.md §4: the official inference pre-processing."""
        return {
            "kind": "official",
            "normalize_bound": 0.95,
            "merge_distance_fraction": 0.01,
            "surface_samples": 50000,
            "round_float16": True,
            "n_points": cfg.n_points,
        }

    @classmethod
    def card_summary(cls) -> list[str]:
        return [
            "The released Mesh Silksong network (`arch: official`, `docs/official_network.md` §3),",
            "re-implemented from that description: learned queries cross-attending to 4,096 surface",
            "points + normals, conditioner projections, then a pre-norm decoder with L2 qk-norm self-",
            "and cross-attention (learned memory slots) and GLU feed-forward, exported for the Silk C++",
            "runtime per `docs/model_contract.md` (version 3).",
        ]

    def __init__(self, cfg: ModelConfig):
        super().__init__()
        vocab = load_vocab()
        self.cfg = cfg
        self.bos_id, self.eos_id, self.pad_id = vocab.bos_id, vocab.eos_id, vocab.pad_id
        self.n_logits = vocab.model_vocab_size
        d, w = cfg.d_model, cfg.encoder_width
        for name in TYPE_VECTOR_NAMES:
            self.register_parameter(name, nn.Parameter(torch.zeros(1, d)))
        self.sos_token = nn.Parameter(torch.zeros(d))
        self.token_embed = nn.Embedding(self.n_logits, d)
        self.abs_pos_emb = nn.Embedding(cfg.max_seq_len - 1, d)
        self.point_encoder = OfficialPointEncoder(
            w, cfg.encoder_heads, cfg.encoder_layers, cfg.n_queries, cfg.fourier_freqs
        )
        self.cond_head_proj = nn.Linear(w, cfg.context_dim)
        self.cond_proj = nn.Linear(w, cfg.context_dim)
        self.layers = nn.ModuleList(OfficialBlock(cfg) for _ in range(cfg.n_layers))
        self.final_norm = nn.LayerNorm(d)
        self.to_logits = nn.Linear(d, self.n_logits)
        self.init_buffers()
        self.gradient_checkpointing = False  # training: recompute each decoder layer in backward
        assert len(TYPE_VECTOR_NAMES) == len(TYPE_CLASSES)

    def init_buffers(self) -> None:
        """Non-persistent buffers (again after `to_empty`, which leaves them uninitialised)."""
        self.register_buffer("type_of_id", torch.from_numpy(load_vocab().type_of_id()), persistent=False)

    def init_random(self, std: float = 0.02, seed: int = 0) -> "OfficialModel":
        """Random weights (benchmarks and tests): normal(std) everywhere, LayerNorms at 1/0 plus noise."""
        g = torch.Generator().manual_seed(seed)
        with torch.no_grad():
            for name, p in self.named_parameters():
                p.copy_(torch.randn(p.shape, generator=g) * std)
                if name.endswith("norm.weight") or ".ln_" in name and name.endswith("weight"):
                    p.add_(1.0)
        return self

    def embed(self, ids: torch.Tensor, positions: torch.Tensor) -> torch.Tensor:
        """Contract ids/positions -> decoder input rows (module docstring)."""
        types = torch.cat(
            [torch.zeros_like(self.sos_token).unsqueeze(0)] + [getattr(self, n) for n in TYPE_VECTOR_NAMES], dim=0
        )
        tok = self.token_embed(ids.clamp(max=self.n_logits - 1))
        pos = self.abs_pos_emb((positions - 1).clamp(min=0))
        rows = tok + pos + types[self.type_of_id[ids]]
        return torch.where((ids == self.bos_id).unsqueeze(-1), self.sos_token, rows)

    def context(self, points: torch.Tensor) -> torch.Tensor:
        """points [B,N,6] -> conditioner output [B,Q,C] (row 0 via cond_head_proj)."""
        lat = self.point_encoder(points)
        return torch.cat([self.cond_head_proj(lat[:, :1]), self.cond_proj(lat[:, 1:])], dim=1)

    def encode_points(self, points: torch.Tensor) -> list[tuple[torch.Tensor, torch.Tensor]]:
        """points [B,N,6] -> per layer (K, V) [B,H,slots+Q,dh], keys normalised."""
        ctx = self.context(points)
        return [layer.cross_kv(ctx) for layer in self.layers]

    def logits(self, x: torch.Tensor) -> torch.Tensor:
        return self.to_logits(self.final_norm(x))

    def forward(self, input_ids: torch.Tensor, points: torch.Tensor, labels: torch.Tensor | None = None):
        """Teacher forcing, same conventions as SilkModel.forward: input_ids [B,S] start with BOS,
        contract positions 0..S-1. Returns logits [B,S,10269], or (loss, logits) with labels."""
        cross = self.encode_points(points)
        pos = torch.arange(input_ids.shape[1], device=input_ids.device).unsqueeze(0)
        x = self.embed(input_ids, pos)
        for layer, (ck, cv) in zip(self.layers, cross):

            def causal(y, layer=layer):
                q, k, v = (split_heads(t, self.cfg.n_heads) for t in layer.self_qkv(y))
                return merge_heads(attend(q, k, v, causal=True, scale=self.cfg.qk_scale)), None

            if self.gradient_checkpointing and self.training:
                x = checkpoint(
                    lambda x, ck, cv, layer=layer, f=causal: layer.block(x, ck, cv, f)[0],
                    x,
                    ck,
                    cv,
                    use_reentrant=False,
                )
            else:
                x, _ = layer.block(x, ck, cv, causal)
        logits = self.logits(x)
        if labels is None:
            return logits
        loss = F.cross_entropy(logits.reshape(-1, logits.shape[-1]), labels.reshape(-1), ignore_index=IGNORE_INDEX)
        return loss, logits
