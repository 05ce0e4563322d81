# SPDX-License-Identifier: MIT
"""The release checkpoint's key layout (official_network.md §2, §5, §6): which keys are skipped, how a
used key maps onto OfficialModel's parameter names, and the sizes its tensor shapes reveal."""

from __future__ import annotations

import re

from .state_dict_file import StateDictError, TensorInfo

WRAPPER_PREFIXES = ("module.", "_orig_mod.")
ENCODER = "conditioner.point_encoder.model.shape_model.encoder."
# Training-only parts of the point encoder (VAE / CLIP heads): present in the file, never run.
UNUSED_PREFIXES = (
    "conditioner.point_encoder.model.shape_projection",
    "conditioner.point_encoder.model.shape_model.pre_kl.",
    "conditioner.point_encoder.model.shape_model.post_kl.",
    "conditioner.point_encoder.model.shape_model.transformer.",
    "conditioner.point_encoder.model.shape_model.geo_decoder.",
)
# decoder.layers.{i}: i % 3 = 0 self-attention, 1 cross-attention, 2 feed-forward.
_NORMS = ("self_norm", "cross_norm", "ff_norm")
_LAYER_LEAVES = (
    {r"1\.(to_q|to_k|to_v|to_out)\.weight": r"self_attn.\1.weight"},
    {r"1\.(to_q|to_k|to_v|to_out)\.weight": r"cross_attn.\1.weight", r"1\.(mem_k|mem_v)": r"cross_attn.\1"},
    {r"1\.ff\.0\.proj\.(weight|bias)": r"ff.proj_in.\1", r"1\.ff\.2\.(weight|bias)": r"ff.proj_out.\1"},
)
_TOP = {
    r"(matrix_in0_embed|matrix_in1_embed|matrix_out_embed|block_embed|offset_embed|sos_token)": r"\1",
    r"(token_embed|abs_pos_emb)\.weight": r"\1.weight",
    r"to_logits\.(weight|bias)": r"to_logits.\1",
    r"decoder\.final_norm\.(weight|bias)": r"final_norm.\1",
    r"conditioner\.(cond_head_proj|cond_proj)\.(weight|bias)": r"\1.\2",
    re.escape(ENCODER) + r"(.+)": r"point_encoder.\1",
}


def strip_wrapper(key: str) -> tuple[str, str]:
    """('module.x', ...) -> ('x', 'module.'); repeated wrappers are all removed."""
    removed = ""
    while key.startswith(WRAPPER_PREFIXES):
        p = next(p for p in WRAPPER_PREFIXES if key.startswith(p))
        key, removed = key[len(p) :], removed + p
    return key, removed


def is_unused(key: str) -> bool:
    return key.startswith(UNUSED_PREFIXES)


def local_name(key: str) -> str | None:
    """Release key -> OfficialModel parameter name, or None for a key outside the layout."""
    m = re.fullmatch(r"decoder\.layers\.(\d+)\.(.+)", key)
    if m:
        i, rest = int(m.group(1)), m.group(2)
        block, kind = i // 3, i % 3
        n = re.fullmatch(r"0\.0\.(weight|bias)", rest)
        if n:
            return f"layers.{block}.{_NORMS[kind]}.{n.group(1)}"
        for pattern, repl in _LAYER_LEAVES[kind].items():
            if re.fullmatch(pattern, rest):
                return f"layers.{block}." + re.sub(pattern, repl, rest)
        return None
    for pattern, repl in _TOP.items():
        if re.fullmatch(pattern, key):
            return re.sub(pattern, repl, key)
    return None


def _shape(infos: dict[str, TensorInfo], key: str, rank: int) -> tuple[int, ...]:
    if key not in infos:
        raise StateDictError(f"missing key '{key}' (needed to read the model's sizes)")
    shape = infos[key].shape
    if len(shape) != rank:
        raise StateDictError(f"key '{key}': shape {list(shape)} should have {rank} dimensions")
    return shape


def _count(infos: dict[str, TensorInfo], pattern: str) -> int:
    return len({m.group(1) for k in infos if (m := re.fullmatch(pattern, k))})


def sizes_from_shapes(infos: dict[str, TensorInfo]) -> dict:
    """The sizes official_network.md §6 reads from tensor shapes (keys already unwrapped)."""
    rows, d = _shape(infos, "token_embed.weight", 2)
    n_layer_entries = _count(infos, r"decoder\.layers\.(\d+)\.0\.0\.weight")
    if n_layer_entries == 0 or n_layer_entries % 3:
        raise StateDictError(
            f"decoder.layers: {n_layer_entries} pre-norm entries, expected a positive "
            "multiple of 3 (self, cross, feed-forward per block)"
        )
    heads, slots, dh = _shape(infos, "decoder.layers.1.1.mem_k", 3)
    ctx = _shape(infos, "decoder.layers.1.1.to_k.weight", 2)[1]
    ff_inner = _shape(infos, "decoder.layers.2.1.ff.0.proj.weight", 2)[0] // 2
    queries, width = _shape(infos, ENCODER + "query", 2)
    in_features = _shape(infos, ENCODER + "input_proj.weight", 2)[1]
    if (in_features - 6) % 6 or in_features <= 6:
        raise StateDictError(f"key '{ENCODER}input_proj.weight': {in_features} input features is not 3 + 6·F + 3")
    if ff_inner % d:
        raise StateDictError(f"feed-forward width {ff_inner} is not a multiple of the model width {d}")
    return {
        "token_rows": rows,
        "d_model": d,
        "n_layers": n_layer_entries // 3,
        "n_heads": heads,
        "attn_head_dim": dh,
        "memory_slots": slots,
        "context_dim": ctx,
        "ff_mult": ff_inner // d,
        "n_queries": queries,
        "encoder_width": width,
        "encoder_layers": _count(infos, re.escape(ENCODER) + r"self_attn\.resblocks\.(\d+)\..*"),
        "fourier_freqs": (in_features - 6) // 6,
        "max_seq_len": _shape(infos, "abs_pos_emb.weight", 2)[0] + 1,
    }


def release_name(local: str) -> str:
    """OfficialModel parameter name -> release key (inverse of local_name)."""
    m = re.fullmatch(r"layers\.(\d+)\.([a-z_]+)\.(.+)", local)
    if m:
        block, part, rest = int(m.group(1)), m.group(2), m.group(3)
        if part in _NORMS:
            return f"decoder.layers.{3 * block + _NORMS.index(part)}.0.0.{rest}"
        kind, leaf = {
            "self_attn": (0, rest),
            "cross_attn": (1, rest),
            "ff": (2, rest.replace("proj_in.", "ff.0.proj.").replace("proj_out.", "ff.2.")),
        }[part]
        return f"decoder.layers.{3 * block + kind}.1.{leaf}"
    for local_prefix, release_prefix in (
        ("point_encoder.", ENCODER),
        ("final_norm.", "decoder.final_norm."),
        ("cond_head_proj.", "conditioner.cond_head_proj."),
        ("cond_proj.", "conditioner.cond_proj."),
    ):
        if local.startswith(local_prefix):
            return release_prefix + local[len(local_prefix) :]
    return local
