# SPDX-License-Identifier: MIT
"""A 20-step run on a handful of meshes lowers the loss, and an interrupted run resumed from its
checkpoint ends with exactly the weights of an uninterrupted one."""

from __future__ import annotations

import json

import numpy as np
import pytest
import torch

from silk_export.checkpoint import model_from_checkpoint
from silk_export.models.configs import ModelConfig
from silk_export.data.dataset_index import build_index
from silk_export.models.silk_model import SilkModel
from silk_export.data.samples import MeshCache
from silk_export.json_io import jsonl_line
from silk_export.training.train import TrainArgs, evaluate_loss, seed_everything, train

TEST_CFG = ModelConfig(
    "test",
    d_model=64,
    n_layers=2,
    n_heads=2,
    n_latents=16,
    max_seq_len=512,
    encoder_layers=1,
    fourier_freqs=4,
    n_points=256,
)
MESHES = ["cube", "octahedron", "tetrahedron", "torus_12x8", "two_components", "grid"]


@pytest.fixture(scope="module")
def data(golden_dir, dev_dir, tmp_path_factory, mesh_folder):
    root = mesh_folder(golden_dir, MESHES)
    out = tmp_path_factory.mktemp("index")
    summary = build_index(root, out, dev_dir)
    assert summary["meshes"] == len(MESHES) and not summary["refusals"]
    rows = [json.loads(x) for x in open(out / "index.jsonl")]
    for r in rows:
        r["split"] = "train"  # these few meshes are all training data here
    (out / "index.jsonl").write_text("".join(jsonl_line(r) for r in rows))
    return root, out / "index.jsonl", rows


def args(data, out, steps, **kw):
    root, index, _ = data
    base = dict(
        index=str(index),
        root=str(root),
        out=str(out),
        steps=steps,
        batch_size=3,
        lr=3e-3,
        lr_min=1e-3,
        seed=0,
        threads=1,
        log_every=1,
        val_every=0,
        ckpt_minutes=1e9,
        progress=False,
        augment=False,
        model_config=TEST_CFG.to_dict(),
    )
    base.update(kw)
    return TrainArgs(**base)


def fixed_samples(data):
    root, _, rows = data
    cache = MeshCache(root, rows)
    rng = np.random.default_rng(123)
    return [
        cache.sample(i, rng, TEST_CFG.max_tokens, augment=False, n_points=TEST_CFG.n_points) for i in range(len(cache))
    ]


def test_twenty_steps_lower_the_loss(data, tmp_path):
    torch.set_num_threads(1)
    seed_everything(0)
    initial = evaluate_loss(SilkModel(TEST_CFG), fixed_samples(data), "cpu")
    res = train(args(data, tmp_path, 20))
    assert res["step"] == 20
    model, ck = model_from_checkpoint(tmp_path / "checkpoint.pt")
    final = evaluate_loss(model, fixed_samples(data), "cpu")
    assert initial > 8.5  # ~ln(10269) at initialisation
    assert final < initial - 1.0, (initial, final)
    log = [json.loads(x) for x in open(tmp_path / "log.jsonl")]
    assert [r["step"] for r in log] == list(range(1, 21))
    assert (tmp_path / "loss.png").stat().st_size > 1000 and (tmp_path / "loss.csv").exists()


def test_resume_reproduces_the_uninterrupted_run(data, tmp_path):
    torch.set_num_threads(1)
    train(args(data, tmp_path / "full", 6))
    train(args(data, tmp_path / "split", 6, max_minutes=1e-9))  # stops (and checkpoints) after step 1
    first = torch.load(tmp_path / "split" / "checkpoint.pt", weights_only=False)["step"]
    assert 1 <= first < 6
    train(args(data, tmp_path / "split", 6))
    a, _ = model_from_checkpoint(tmp_path / "full" / "checkpoint.pt")
    b, ck = model_from_checkpoint(tmp_path / "split" / "checkpoint.pt")
    assert ck["step"] == 6
    for (n, p), (_, q) in zip(a.state_dict().items(), b.state_dict().items()):
        assert torch.equal(p, q), n


def test_packed_checkpoint_is_smaller_and_resumes_the_run(data, tmp_path):
    """The repository's resumable checkpoint: bf16 optimizer moments, same weights and step; a run
    resumed from it continues the same schedule and lands close to the uninterrupted run."""
    from silk_export.checkpoint import pack_checkpoint

    torch.set_num_threads(1)
    train(args(data, tmp_path / "full", 6))
    train(args(data, tmp_path / "split", 6, max_minutes=1e-9))  # step 1 (or a few) only
    full_ck = tmp_path / "split" / "checkpoint.pt"
    step = torch.load(full_ck, weights_only=False)["step"]
    info = pack_checkpoint(full_ck, tmp_path / "packed.pt")
    assert info["step"] == step and info["packed_tensors"] > 0
    assert info["bytes"] < 0.75 * full_ck.stat().st_size  # moments are 2/3 of the fp32 bytes
    packed = torch.load(tmp_path / "packed.pt", weights_only=False)
    moments = [v for st in packed["optimizer"]["state"].values() for k, v in st.items() if k.startswith("exp_avg")]
    assert moments and all(v.dtype == torch.bfloat16 for v in moments)
    ref = torch.load(full_ck, weights_only=False)
    for n, p in ref["model"].items():
        assert torch.equal(p, packed["model"][n]), n
    with pytest.raises(ValueError, match="over the 1,000-byte limit"):
        pack_checkpoint(full_ck, tmp_path / "tiny.pt", max_bytes=1000)
    assert not (tmp_path / "tiny.pt").exists()

    resumed = tmp_path / "resumed"
    resumed.mkdir()
    (resumed / "checkpoint.pt").write_bytes((tmp_path / "packed.pt").read_bytes())
    res = train(args(data, resumed, 6))
    assert res["step"] == 6
    a, _ = model_from_checkpoint(tmp_path / "full" / "checkpoint.pt")
    b, _ = model_from_checkpoint(resumed / "checkpoint.pt")
    worst = max((p - q).abs().max().item() for p, q in zip(a.state_dict().values(), b.state_dict().values()))
    assert worst < 5e-3, worst  # only the moments' rounding differs


def test_generate_samples_legal_ids_and_writes_the_layout(data, tmp_path, golden_dir):
    from silk_export.evaluation.generate import generate_paths, pick_from_index

    train(args(data, tmp_path / "run", 2))
    root, index, rows = data
    picked = pick_from_index(index, root, "train", 2, 10_000)
    assert len(picked) == 2 and all(p.exists() for p in picked)
    res = generate_paths(tmp_path / "run" / "checkpoint.pt", picked, tmp_path / "gen", max_tokens=20, seed=1)
    assert res["inputs"] == 2 and (tmp_path / "gen" / "generate.json").exists()
    for row in res["meshes"]:
        assert row["tokens"] + row["eos"] <= 20  # at most max_tokens ids, EOS included
        assert (tmp_path / "gen" / "reference" / f"{row['name']}.obj").exists()


def test_workers_checkpointing_and_micro_batches_keep_the_losses(data, tmp_path):
    """DataLoader workers and gradient checkpointing change nothing; padded micro-batches of 3
    (instead of one sequence at a time) and bf16 autocast change only rounding."""
    torch.set_num_threads(1)

    def run_losses(name, **kw):
        train(args(data, tmp_path / name, 4, **kw))
        return [json.loads(x)["loss"] for x in open(tmp_path / name / "log.jsonl")]

    base = run_losses("base")
    assert run_losses("workers", workers=2, grad_checkpoint=True) == base
    np.testing.assert_allclose(run_losses("micro", micro_batch=3), base, atol=1e-4)
    bf16 = run_losses("bf16", precision="bf16")
    assert bf16 != base  # autocast is on
    np.testing.assert_allclose(bf16, base, atol=0.1)


def test_conditioning_gap_is_zero_only_for_a_model_blind_to_its_points(data, tmp_path):
    """`silk-export loss` scores the tokens again with each mesh given the next mesh's points."""
    from silk_export.evaluation.split_loss import other_points, split_loss

    torch.set_num_threads(1)
    root, index, _ = data
    train(args(data, tmp_path, 10))
    samples = fixed_samples(data)
    swapped = other_points(samples)
    assert all(np.array_equal(a.tokens, b.tokens) for a, b in zip(samples, swapped))
    assert all(np.array_equal(swapped[i].points, samples[(i + 1) % len(samples)].points) for i in range(len(samples)))
    seeing = split_loss(tmp_path / "checkpoint.pt", index, root, "train", baseline_split=None)
    assert seeing["meshes"] == len(MESHES)
    assert abs(seeing["conditioning_gap"]) > 1e-4, seeing
    assert seeing["loss_other_points"] == pytest.approx(seeing["loss"] + seeing["conditioning_gap"])
    # The same weights with the point embedding zeroed: every mesh's encoder output is the same.
    ck = torch.load(tmp_path / "checkpoint.pt", map_location="cpu", weights_only=False)
    ck["model"]["encoder.embed.proj.weight"].zero_()
    torch.save(ck, tmp_path / "blind.pt")
    blind = split_loss(tmp_path / "blind.pt", index, root, "train", baseline_split=None)
    assert blind["conditioning_gap"] == 0.0, blind
    assert "conditioning_gap" not in split_loss(
        tmp_path / "checkpoint.pt", index, root, "train", limit=1, baseline_split=None
    )
