# SPDX-License-Identifier: MIT
"""The Mesh Silksong generator: point encoder + decoder-only transformer whose pre-norm layers
do causal self-attention, cross-attention to the point latents, then an MLP. Embeddings are
token + type (token_format.md §9) + learned absolute position (BOS at 0, mesh token t at t + 1)."""

from __future__ import annotations

import torch
import torch.nn.functional as F
from torch import nn
from torch.utils.checkpoint import checkpoint

from ..vocab import TYPE_CLASSES, load_vocab
from .architecture import IGNORE_INDEX, Architecture
from .configs import ModelConfig
from .layers import FeedForward, MultiHeadAttention, attend, merge_heads, split_heads
from .point_encoder import PointEncoder


class DecoderLayer(nn.Module):
    fsdp_forward_methods = ("cross_kv",)  # SilkModel calls it before the layers run (training/distributed.py)

    def __init__(self, cfg: ModelConfig):
        super().__init__()
        d, h = cfg.d_model, cfg.n_heads
        self.norm_self = nn.LayerNorm(d)
        self.self_attn = MultiHeadAttention(d, h)
        self.norm_cross = nn.LayerNorm(d)
        self.cross_attn = MultiHeadAttention(d, h)
        self.norm_ff = nn.LayerNorm(d)
        self.ff = FeedForward(d, cfg.ff_mult)

    def cross_kv(self, latents: torch.Tensor) -> tuple[torch.Tensor, torch.Tensor]:
        """This layer's cross-attention K/V of the latents, [B,H,M,D] each."""
        return self.cross_attn.keys_values(latents)

    def self_qkv(self, y: torch.Tensor) -> tuple[torch.Tensor, torch.Tensor, torch.Tensor]:
        """Self-attention q, k, v of the normed input, [B,T,d] each (what the ONNX graph feeds GQA)."""
        a = self.self_attn
        return a.q(y), a.k(y), a.v(y)

    def forward(self, x, cross_k, cross_v, fused=True):
        """x [B,T,d] with causal self-attention over its own rows (teacher forcing) -> [B,T,d]."""
        h = self.self_attn.n_heads

        def self_attention(y):
            q = split_heads(self.self_attn.q(y), h)
            k, v = self.self_attn.keys_values(y)
            return merge_heads(attend(q, k, v, causal=True, fused=fused)), None

        return self.block(x, cross_k, cross_v, self_attention, fused)[0]

    def block(self, x, cross_k, cross_v, self_attention, fused=True):
        """The layer's residual structure with the self-attention step supplied by the caller:
        self_attention(normed x [B,T,d]) -> (heads merged [B,T,d], anything to hand back), using
        self.self_attn's projections. Training and the ONNX decoder graph differ only there."""
        a, extra = self_attention(self.norm_self(x))
        x = x + self.self_attn.o(a)
        y = self.norm_cross(x)
        q = split_heads(self.cross_attn.q(y), self.cross_attn.n_heads)
        x = x + self.cross_attn.o(merge_heads(attend(q, cross_k, cross_v, fused=fused)))
        x = x + self.ff(self.norm_ff(x))
        return x, extra


class SilkModel(Architecture):
    """Architecture "silk" (model.json version 2)."""

    name = "silk"
    model_version = 2

    @classmethod
    def preprocessing(cls, cfg: ModelConfig) -> dict:
        return {
            "kind": "silk",
            "normalize_bound": 0.95,
            "merge_distance_fraction": 0.0,
            "surface_samples": 0,
            "round_float16": False,
            "n_points": cfg.n_points,
        }

    @classmethod
    def card_summary(cls) -> list[str]:
        return [
            "A point-cloud-conditioned autoregressive generator of Mesh Silksong token sequences",
            "(decoder-only transformer with cross-attention to perceiver latents of 4,096 surface",
            "points + normals), exported for the Silk C++ runtime per `docs/model_contract.md`.",
        ]

    def __init__(self, cfg: ModelConfig):
        super().__init__()
        vocab = load_vocab()
        self.cfg = cfg
        self.bos_id = vocab.bos_id
        self.eos_id = vocab.eos_id
        self.pad_id = vocab.pad_id
        self.n_logits = vocab.model_vocab_size
        d = cfg.d_model
        self.encoder = PointEncoder(cfg)
        self.tok_emb = nn.Embedding(vocab.embedding_rows, d)
        self.type_emb = nn.Parameter(torch.zeros(len(TYPE_CLASSES), d))
        self.register_buffer("type_of_id", torch.from_numpy(vocab.type_of_id()), persistent=False)
        self.pos_emb = nn.Embedding(cfg.max_seq_len, d)
        self.layers = nn.ModuleList(DecoderLayer(cfg) for _ in range(cfg.n_layers))
        self.norm = nn.LayerNorm(d)
        self.head = nn.Linear(d, self.n_logits)
        self.apply(self._init)
        nn.init.normal_(self.type_emb, std=0.02)
        self.gradient_checkpointing = False  # training: recompute each decoder layer in backward

    @staticmethod
    def _init(m: nn.Module) -> None:
        if isinstance(m, nn.Linear):
            nn.init.normal_(m.weight, std=0.02)
            if m.bias is not None:
                nn.init.zeros_(m.bias)
        elif isinstance(m, nn.Embedding):
            nn.init.normal_(m.weight, std=0.02)

    def embed(self, ids: torch.Tensor, positions: torch.Tensor) -> torch.Tensor:
        types = torch.cat([torch.zeros_like(self.type_emb[:1]), self.type_emb], dim=0)
        return self.tok_emb(ids) + types[self.type_of_id[ids]] + self.pos_emb(positions)

    def encode_points(self, points: torch.Tensor) -> list[tuple[torch.Tensor, torch.Tensor]]:
        """points [B,N,6] -> per layer (K, V) [B,H,M,D]."""
        lat = self.encoder(points)
        return [layer.cross_kv(lat) for layer in self.layers]

    def logits(self, x: torch.Tensor) -> torch.Tensor:
        return self.head(self.norm(x))

    def forward(self, input_ids: torch.Tensor, points: torch.Tensor, labels: torch.Tensor | None = None):
        """Teacher forcing. input_ids [B,S] start with BOS (PAD after the end); positions 0..S-1.
        Returns logits [B,S,10269], or (loss, logits) with labels (IGNORE_INDEX = not scored)."""
        cross = self.encode_points(points)
        pos = torch.arange(input_ids.shape[1], device=input_ids.device).unsqueeze(0)
        x = self.embed(input_ids, pos)
        for layer, (ck, cv) in zip(self.layers, cross):
            if self.gradient_checkpointing and self.training:
                x = checkpoint(lambda x, ck, cv, layer=layer: layer(x, ck, cv), x, ck, cv, use_reentrant=False)
            else:
                x = layer(x, ck, cv)
        logits = self.logits(x)
        if labels is None:
            return logits
        loss = F.cross_entropy(logits.reshape(-1, logits.shape[-1]), labels.reshape(-1), ignore_index=IGNORE_INDEX)
        return loss, logits
