# SPDX-License-Identifier: MIT
"""Loads a release-layout Mesh Silksong checkpoint into OfficialModel, strictly: every used key
present with the right shape, unknown keys are errors, wrapper prefixes stripped and reported,
the training-only point-encoder parts skipped and counted. Tensors are read one at a time."""

from __future__ import annotations

import json
from collections import Counter
from dataclasses import dataclass, field
from pathlib import Path

import torch
from tqdm import tqdm

from ..models.configs import ModelConfig
from ..models.finite import nonfinite_message, nonfinite_summary
from ..vocab import TYPE_CLASSES, load_vocab
from .keys import is_unused, local_name, release_name, sizes_from_shapes, strip_wrapper
from .state_dict_file import StateDictError, open_state_dict

# Values no tensor shape reveals (official_network.md §6), at the release's settings.
RELEASE_DEFAULTS = {"encoder_heads": 12, "qk_scale": 10.0, "n_points": 4096}
# Sizes of the release checkpoint (official_network.md §2), for random-weight models of its shape.
RELEASE_SIZES = {
    "token_rows": 10269,
    "d_model": 1024,
    "n_layers": 24,
    "n_heads": 16,
    "attn_head_dim": 64,
    "memory_slots": 4,
    "context_dim": 1024,
    "ff_mult": 4,
    "n_queries": 257,
    "encoder_width": 768,
    "encoder_layers": 8,
    "fourier_freqs": 8,
    "max_seq_len": 10241,
}
_TYPE_VECTOR_OF_CLASS = dict(
    zip(TYPE_CLASSES, ("matrix_in0_embed", "matrix_in1_embed", "matrix_out_embed", "block_embed", "offset_embed"))
)


@dataclass
class LoadReport:
    tensors: int = 0
    used: int = 0
    skipped_unused: int = 0
    stripped_prefixes: dict = field(default_factory=dict)
    source_dtypes: dict = field(default_factory=dict)
    parameters: int = 0


def settings_from_config_file(path: Path, sizes: dict) -> dict:
    """The fixture's config.json format: the values shapes cannot give, and a cross-check of the
    ones they can (a disagreement is an error naming the field)."""
    try:
        c = json.loads(Path(path).read_text())
    except (OSError, json.JSONDecodeError) as e:
        raise StateDictError(f"--config {path}: {e}") from None
    dec, enc, vocab = c.get("decoder", {}), c.get("point_encoder", {}), c.get("vocab", {})
    checks = {
        ("decoder", "dim"): sizes["d_model"],
        ("decoder", "depth"): sizes["n_layers"],
        ("decoder", "heads"): sizes["n_heads"],
        ("decoder", "dim_head"): sizes["attn_head_dim"],
        ("decoder", "max_seq_len"): sizes["max_seq_len"] - 1,
        ("conditioner", "context_dim"): sizes["context_dim"],
        ("point_encoder", "width"): sizes["encoder_width"],
        ("point_encoder", "num_encoder_layers"): sizes["encoder_layers"],
        ("point_encoder", "num_freqs"): sizes["fourier_freqs"],
    }
    for (section, key), have in checks.items():
        want = c.get(section, {}).get(key)
        if want is not None and want != have:
            raise StateDictError(f"--config {path}: {section}.{key} = {want}, but the checkpoint's shapes say {have}")
    layout = load_vocab().layout["ranges"]
    for cls, name in _TYPE_VECTOR_OF_CLASS.items():
        want = vocab.get("type_embedding_ranges", {}).get(name)
        if want is not None and list(want) != list(layout[cls]):
            raise StateDictError(
                f"--config {path}: type range {name} = {want} differs from the tokenizer's "
                f"{layout[cls]}; this token format cannot serve that model"
            )
    out = {}
    if "heads" in enc:
        out["encoder_heads"] = int(enc["heads"])
    if "num_points" in enc:
        out["n_points"] = int(enc["num_points"])
    if "qk_norm_scale" in dec:
        out["qk_scale"] = float(dec["qk_norm_scale"])
    return out


def official_config(sizes: dict, settings: dict, name: str = "official") -> ModelConfig:
    vocab_rows = load_vocab().model_vocab_size
    if sizes["token_rows"] != vocab_rows:
        raise StateDictError(
            f"key 'token_embed.weight': {sizes['token_rows']} rows, expected {vocab_rows} (10267 token ids + EOS + PAD)"
        )
    s = {**RELEASE_DEFAULTS, **settings}
    if sizes["encoder_width"] % s["encoder_heads"]:
        raise StateDictError(
            f"point encoder width {sizes['encoder_width']} is not divisible by its "
            f"{s['encoder_heads']} heads (set point_encoder.heads with --config)"
        )
    return ModelConfig(
        name,
        d_model=sizes["d_model"],
        n_layers=sizes["n_layers"],
        n_heads=sizes["n_heads"],
        n_latents=sizes["memory_slots"] + sizes["n_queries"],
        max_seq_len=sizes["max_seq_len"],
        encoder_layers=sizes["encoder_layers"],
        ff_mult=sizes["ff_mult"],
        fourier_freqs=sizes["fourier_freqs"],
        n_points=s["n_points"],
        arch="official",
        attn_head_dim=sizes["attn_head_dim"],
        context_dim=sizes["context_dim"],
        n_queries=sizes["n_queries"],
        memory_slots=sizes["memory_slots"],
        encoder_width=sizes["encoder_width"],
        encoder_heads=s["encoder_heads"],
        qk_scale=s["qk_scale"],
    )


def _unwrap(infos: dict, report: LoadReport) -> dict[str, str]:
    """unwrapped key -> key in the file; counts stripped prefixes and skipped unused keys."""
    keys, stripped = {}, Counter()
    for raw in infos:
        key, prefix = strip_wrapper(raw)
        if prefix:
            stripped[prefix] += 1
        if key in keys:
            raise StateDictError(f"key '{key}' appears twice ('{keys[key]}' and '{raw}')")
        if is_unused(key):
            report.skipped_unused += 1
        else:
            keys[key] = raw
    report.stripped_prefixes = dict(stripped)
    return keys


def check_layout(keys: dict[str, str], infos: dict, params: dict) -> None:
    """Every problem at once, each naming its key: unknown, missing, misshaped."""
    problems = []
    for key, raw in keys.items():
        name = local_name(key)
        if name not in params:
            problems.append(f"unknown key '{raw}' (not part of the released network's layout)")
        elif tuple(params[name].shape) != infos[raw].shape:
            problems.append(f"key '{raw}': shape {list(infos[raw].shape)}, expected {list(params[name].shape)}")
    present = {local_name(k) for k in keys}
    problems += [
        f"missing key '{release_name(n)}' (shape {list(p.shape)})" for n, p in params.items() if n not in present
    ]
    if problems:
        raise StateDictError(f"{len(problems)} problem(s) in the checkpoint:\n  " + "\n  ".join(problems))


def load_official(path: Path, config_path: Path | None = None, progress: bool = True):
    """-> (OfficialModel in float32, eval mode; LoadReport). Raises StateDictError naming the key (also
    for a tensor holding NaN or Inf: every such key with its counts)."""
    from .model import OfficialModel

    src = open_state_dict(path)
    infos = src.infos()
    report = LoadReport(tensors=len(infos))
    keys = _unwrap(infos, report)
    sizes = sizes_from_shapes({k: infos[raw] for k, raw in keys.items()})
    settings = settings_from_config_file(config_path, sizes) if config_path else {}
    cfg = official_config(sizes, settings)
    with torch.device("meta"):
        model = OfficialModel(cfg)
    params = dict(model.named_parameters())
    check_layout(keys, infos, params)
    model.to_empty(device="cpu")
    model.init_buffers()
    params = dict(model.named_parameters())  # to_empty made new tensors
    total = sum(infos[raw].dtype.itemsize * params[local_name(k)].numel() for k, raw in keys.items())
    dtypes, nonfinite = Counter(), []
    with (
        torch.no_grad(),
        tqdm(total=total, unit="B", unit_scale=True, desc="read weights", disable=not progress) as bar,
    ):
        for key, raw in keys.items():
            t = src.read(raw)
            dtypes[str(t.dtype).replace("torch.", "")] += 1
            if (found := nonfinite_summary(t)) is not None:
                nonfinite.append(f"key '{raw}': {found}")
            params[local_name(key)].copy_(t)
            bar.update(t.numel() * t.element_size())
            del t
    if nonfinite:
        raise StateDictError(nonfinite_message(str(path), nonfinite))
    report.used, report.source_dtypes = len(keys), dict(dtypes)
    report.parameters = sum(p.numel() for p in params.values())
    return model.eval(), report
