# SPDX-License-Identifier: MIT
"""PyTorch generation (evaluation/generate.py) for every registered architecture, through the
Architecture interface only: Architecture.step's KV-cache decoding gives the teacher-forced
forward pass's logits, sample_tokens and `silk-export generate` produce ids from a tiny random
model of each architecture, and with the official fixture's weights (official-fixture/) the
PyTorch loop reproduces the official implementation's 100 greedy ids."""

from __future__ import annotations

import json

import numpy as np
import pytest
import torch

from silk_export.evaluation.generate import generate_paths, sample_tokens
from silk_export.models.architecture import Architecture
from silk_export.checkpoint import model_from_checkpoint, save_state
from silk_export.models.configs import ModelConfig
from silk_export.registry import ARCHITECTURES, get_architecture
from silk_export.official.checkpoint import load_official

# One tiny configuration per registered architecture (a new architecture needs its entry here).
TINY = {
    "silk": ModelConfig(
        "tiny-silk", d_model=64, n_layers=2, n_heads=2, n_latents=16, max_seq_len=64, encoder_layers=1, n_points=128
    ),
    "official": ModelConfig(
        "tiny-official",
        d_model=32,
        n_layers=2,
        n_heads=2,
        n_latents=4 + 9,
        max_seq_len=64,
        encoder_layers=1,
        n_points=128,
        arch="official",
        attn_head_dim=16,
        context_dim=24,
        n_queries=9,
        memory_slots=4,
        encoder_width=16,
        encoder_heads=2,
        qk_scale=10.0,
    ),
}


def tiny_model(name: str) -> Architecture:
    """A model of the architecture with every weight perturbed (no parameter left at 0 or 1)."""
    torch.manual_seed(0)
    model = get_architecture(name).build(TINY[name])
    g = torch.Generator().manual_seed(1)
    with torch.no_grad():
        for p in model.parameters():
            p.add_(torch.randn(p.shape, generator=g) * 0.1)
    return model.eval()


def random_points(cfg: ModelConfig) -> np.ndarray:
    pts = np.random.default_rng(2).standard_normal((cfg.n_points, 6)).astype(np.float32)
    pts[:, 3:] /= np.linalg.norm(pts[:, 3:], axis=1, keepdims=True)
    return pts


def test_every_registered_architecture_implements_the_interface():
    assert set(ARCHITECTURES) == set(TINY)
    for name, cls in ARCHITECTURES.items():
        assert issubclass(cls, Architecture) and cls.name == name
        assert cls.points_kind(TINY[name]) == cls.preprocessing(TINY[name])["kind"]
        assert cls.card_summary() and all(isinstance(line, str) for line in cls.card_summary())


@pytest.mark.parametrize("name", sorted(TINY))
def test_step_with_a_kv_cache_gives_the_teacher_forced_logits(name):
    model = tiny_model(name)
    points = torch.from_numpy(random_points(model.cfg)).unsqueeze(0)
    ids = torch.tensor([[model.bos_id, 3, 250, 700, 5700, 6200, 9000, 40, 4000]])
    with torch.no_grad():
        want = model(ids, points)
        cross = model.encode_points(points)
        past, got = model.empty_cache(), []
        for lo, hi in ((0, 4), (4, 5), (5, 9)):  # a chunk, one token, a chunk
            logits, new = model.step(ids[:, lo:hi], torch.arange(lo, hi).unsqueeze(0), past, cross)
            past = [(torch.cat([pk, kn], 2), torch.cat([pv, vn], 2)) for (pk, pv), (kn, vn) in zip(past, new)]
            got.append(logits)
    torch.testing.assert_close(torch.cat(got, dim=1), want, atol=1e-4, rtol=1e-4)
    assert past[0][0].shape == (1, model.cfg.n_heads, 9, model.cfg.head_dim)


@pytest.mark.parametrize("name", sorted(TINY))
def test_sample_tokens_generates_with_each_architecture(name):
    model = tiny_model(name)
    toks, eos = sample_tokens(model, random_points(model.cfg), 12, 1.0, 50, torch.Generator().manual_seed(3))
    assert toks.dtype == np.int32 and (len(toks) == 12 or eos)
    assert all(0 <= t < model.n_logits and t not in (model.pad_id, model.eos_id) for t in toks)


@pytest.mark.parametrize("name", sorted(TINY))
def test_generate_command_runs_a_checkpoint_of_each_architecture(name, lib_path, dev_dir, tmp_path):
    """`silk-export generate --model CHECKPOINT` end to end: the architecture's point pre-processing
    through libsilk, sampling, decoding through libsilk, generate.json."""
    model = tiny_model(name)
    save_state(tmp_path / "checkpoint.pt", model.cfg.to_dict(), model.state_dict(), None, 0, {})
    loaded, _ = model_from_checkpoint(tmp_path / "checkpoint.pt")
    assert type(loaded) is type(model)
    mesh = sorted(dev_dir.glob("*.obj"))[0]
    res = generate_paths(tmp_path / "checkpoint.pt", [mesh], tmp_path / "gen", max_tokens=6, seed=4)
    assert res["inputs"] == 1 and res["meshes"][0]["tokens"] + res["meshes"][0]["eos"] <= 6
    assert json.loads((tmp_path / "gen" / "generate.json").read_text()) == res
    assert (tmp_path / "gen" / "reference" / f"{mesh.name.split('.')[0]}.obj").exists()


def test_official_fixture_greedy_ids_through_step(shared):
    """Top-k 1 sampling from the fixture's weights and points = the official loop's greedy.txt."""
    fixture = shared / "official-fixture"
    if not (fixture / "model.safetensors").exists():
        pytest.skip(f"no official fixture in {fixture}")
    model, _ = load_official(fixture / "model.safetensors", fixture / "config.json", progress=False)
    want = [int(x) for x in (fixture / "greedy.txt").read_text().split()]
    toks, eos = sample_tokens(
        model, np.load(fixture / "points.npy"), len(want), 1.0, 1, torch.Generator().manual_seed(0)
    )
    assert not eos and toks.tolist() == want
