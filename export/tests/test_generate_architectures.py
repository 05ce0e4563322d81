# SPDX-License-Identifier: MIT
"""Every registered architecture through the Architecture interface only: Architecture.step's
KV-cache decoding gives the teacher-forced forward pass's logits, `silk-export generate` runs a
checkpoint of each through libsilk (exported first) with silkgen's ids for the same seed, and with
the official fixture's weights (official-fixture/) greedy steps reproduce the official
implementation's 100 greedy ids."""

from __future__ import annotations

import json
import subprocess

import numpy as np
import pytest
import torch

import silk_mesh
from silk_export.evaluation.generate import export_checkpoint, generate_paths
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


@pytest.mark.skipif(not silk_mesh.generation_available(), reason="libsilk without onnxruntime")
@pytest.mark.parametrize("name", sorted(TINY))
def test_generate_command_runs_a_checkpoint_of_each_architecture(name, dev_dir, silkgen, tmp_path):
    """`silk-export generate --model CHECKPOINT` end to end: the checkpoint exported, the
    architecture's point pre-processing, grammar-constrained sampling and decoding all in libsilk,
    generate.json; the ids are silkgen's on the same export with the same seed (one sampling chain)."""
    model = tiny_model(name)
    save_state(tmp_path / "checkpoint.pt", model.cfg.to_dict(), model.state_dict(), None, 0, {})
    loaded, _ = model_from_checkpoint(tmp_path / "checkpoint.pt")
    assert type(loaded) is type(model)
    mesh = sorted(dev_dir.glob("*.obj"))[0]
    res = generate_paths(tmp_path / "checkpoint.pt", [mesh], tmp_path / "gen", seed=4, max_tokens=40)
    row = res["meshes"][0]
    assert res["inputs"] == 1 and res["runtime"] == "libsilk" and "error" not in row, row
    assert 0 < row["tokens"] <= 40 and row["stop_reason"] in ("eos", "max_tokens")
    assert json.loads((tmp_path / "gen" / "generate.json").read_text()) == res
    assert (tmp_path / "gen" / "reference" / f"{mesh.name.split('.')[0]}.obj").exists()
    export_checkpoint(tmp_path / "checkpoint.pt", tmp_path / "exported")
    tokens = tmp_path / "silkgen.tokens.txt"
    run = [silkgen, mesh, "--model", tmp_path / "exported", "--seed", "4", "--max-tokens", "40"]
    subprocess.run([*map(str, run), "--tokens", str(tokens), "-o", str(tmp_path / "silkgen.obj")], check=True)
    with silk_mesh.Model(tmp_path / "exported", threads=1) as m, silk_mesh.Generator(m) as gen:
        _, ids, _ = gen.run(mesh, seed=4, max_tokens=40)
    assert [int(x) for x in tokens.read_text().split()] == list(ids) and len(ids) == row["tokens"]


def greedy_ids(model: Architecture, points: np.ndarray, n: int) -> list[int]:
    """n argmax ids (PAD excluded) by Architecture.step with its KV cache, from BOS."""
    with torch.no_grad():
        cross = model.encode_points(torch.from_numpy(points).unsqueeze(0))
        past, ids, out = model.empty_cache(), torch.tensor([[model.bos_id]]), []
        for pos in range(n):
            logits, new = model.step(ids, torch.tensor([[pos]]), past, cross, fused=False)
            past = [(torch.cat([pk, kn], 2), torch.cat([pv, vn], 2)) for (pk, pv), (kn, vn) in zip(past, new)]
            row = logits[0, -1].clone()
            row[model.pad_id] = float("-inf")
            out.append(int(row.argmax()))
            ids = torch.tensor([[out[-1]]])
    return out


def test_official_fixture_greedy_ids_through_step(shared):
    """Greedy steps from the fixture's weights and points = the official loop's greedy.txt."""
    fixture = shared / "official-fixture"
    if not (fixture / "model.safetensors").exists():
        pytest.skip(f"no official fixture in {fixture}")
    model, _ = load_official(fixture / "model.safetensors", fixture / "config.json", progress=False)
    want = [int(x) for x in (fixture / "greedy.txt").read_text().split()]
    assert greedy_ids(model, np.load(fixture / "points.npy"), len(want)) == want
