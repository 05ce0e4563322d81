# SPDX-License-Identifier: MIT
"""Model sizes. `micro` is the CPU-trainable default bundled model; tiny/small/paper follow the
issue (paper = the Mesh Silksong scale: 1024 wide, 24 layers, 16 heads). `arch` picks the network
(silk_export/registry.py): "silk" (ours) or "official" (the released Mesh Silksong network,
whose extra sizes are the fields after `arch`; 0 = not used by the architecture)."""

from __future__ import annotations

from dataclasses import asdict, dataclass


@dataclass(frozen=True)
class ModelConfig:
    name: str
    d_model: int
    n_layers: int
    n_heads: int
    n_latents: int  # perceiver latents the decoder cross-attends to
    max_seq_len: int  # BOS + mesh tokens + EOS (docs/model_contract.md)
    encoder_layers: int = 2  # self-attention blocks over the latents after the point cross-attention
    ff_mult: int = 4
    fourier_freqs: int = 8
    n_points: int = 4096
    arch: str = "silk"
    attn_head_dim: int = 0  # official: attention width per head (heads x 64 need not equal d_model)
    context_dim: int = 0  # official: width of the conditioner output the decoder cross-attends to
    n_queries: int = 0  # official: point-encoder queries (257 = 1 + 256 latents)
    memory_slots: int = 0  # official: cross-attention memory key/values prepended per layer
    encoder_width: int = 0  # official: point-encoder width W
    encoder_heads: int = 0  # official: point-encoder heads (no shape reveals it)
    qk_scale: float = 0.0  # official: attention scale after L2 qk-norm (10)

    def __post_init__(self):
        if self.attn_head_dim == 0 and self.d_model % self.n_heads:
            raise ValueError(f"config {self.name}: d_model must be a multiple of n_heads")
        if self.head_dim % 8:
            raise ValueError(
                f"config {self.name}: the head width must be a whole multiple of 8 "
                "(onnxruntime's GroupQueryAttention in the exported decoder needs it)"
            )

    @property
    def head_dim(self) -> int:
        return self.attn_head_dim or self.d_model // self.n_heads

    @property
    def max_tokens(self) -> int:
        """Longest tokenizer output a training sample may have (BOS and EOS take two slots)."""
        return self.max_seq_len - 2

    def to_dict(self) -> dict:
        return asdict(self)


CONFIGS = {
    # CPU-trainable sizes around the bundled model, compared at equal CPU time
    # (scripts/train_default_model.sh, docs: models/training/README.md).
    "nano": ModelConfig("nano", d_model=96, n_layers=2, n_heads=2, n_latents=32, max_seq_len=2048, encoder_layers=1),
    "micro": ModelConfig("micro", d_model=128, n_layers=3, n_heads=4, n_latents=64, max_seq_len=2048, encoder_layers=1),
    "mini": ModelConfig("mini", d_model=192, n_layers=4, n_heads=4, n_latents=64, max_seq_len=2048, encoder_layers=1),
    "tiny": ModelConfig("tiny", d_model=256, n_layers=6, n_heads=4, n_latents=256, max_seq_len=10241),
    "small": ModelConfig(
        "small", d_model=512, n_layers=12, n_heads=8, n_latents=256, max_seq_len=10241, encoder_layers=4
    ),
    "paper": ModelConfig(
        "paper", d_model=1024, n_layers=24, n_heads=16, n_latents=256, max_seq_len=10241, encoder_layers=8
    ),
}


def get_config(name: str) -> ModelConfig:
    try:
        return CONFIGS[name]
    except KeyError:
        raise ValueError(f"unknown config '{name}' (known: {', '.join(CONFIGS)})") from None


def config_from_dict(d: dict) -> ModelConfig:
    return ModelConfig(**d)
