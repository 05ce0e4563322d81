# SPDX-License-Identifier: MIT
"""Fine-tuning the released network: `train --init-from` loads a release-layout checkpoint (the
official fixture: official architecture and key layout, random weights) through the importer,
trains it with the fine-tuning defaults (lower LR, warm-up) on a few dev meshes and lowers their
loss; `export` writes a model folder (model.json v3, arch official) that silkgen runs."""

from __future__ import annotations

import json
import subprocess

import numpy as np
import pytest
import torch

from silk_export.checkpoint import model_from_checkpoint
from silk_export.cli import main
from silk_export.official.checkpoint import load_official
from silk_export.data.sharded_dataset import ShardedSource, dataset_rows
from silk_export.training.train import TrainArgs, evaluate_loss, val_samples

SMALL_DEV = ["props__shield__hex_01", "props__wrld_hay_la", "props__weap_javelin_shaft_b", "props__shield__round_b_f"]
STEPS = 10


@pytest.fixture(scope="module")
def fixture_dir(shared):
    return shared / "official-fixture"


@pytest.fixture(scope="module")
def run(dev_dir, fixture_dir, tmp_path_factory, mesh_folder):
    data = mesh_folder(dev_dir, SMALL_DEV)
    out = tmp_path_factory.mktemp("ft")
    torch.set_num_threads(1)
    assert (
        main(
            [
                "train",
                "--data",
                str(data),
                "--init-from",
                str(fixture_dir / "model.safetensors"),
                "--init-config",
                str(fixture_dir / "config.json"),
                "--steps",
                str(STEPS),
                "--batch-size",
                "4",
                "--out",
                str(out),
                "--threads",
                "1",
                "--log-every",
                "1",
                "--val-every",
                "0",
                "--no-progress",
            ]
        )
        == 0
    )
    return data, out


def test_fine_tuning_defaults_are_a_lower_lr_with_warm_up():
    assert TrainArgs(init_from="m.safetensors", steps=1000).schedule() == (2e-5, 2e-6, 100)
    assert TrainArgs(steps=1000).schedule() == (1e-4, 5e-5, 0)
    assert TrainArgs(init_from="m.safetensors", steps=1000, lr=1e-5, warmup=7).schedule() == (1e-5, 2e-6, 7)


def test_ten_steps_lower_the_loss_of_the_released_network(run, fixture_dir):
    _, out = run
    log = [json.loads(x) for x in open(out / "log.jsonl")]
    assert [r["step"] for r in log] == list(range(1, STEPS + 1)) and log[0]["lr"] == pytest.approx(2e-5)
    initial, _ = load_official(fixture_dir / "model.safetensors", fixture_dir / "config.json", progress=False)
    tuned, ck = model_from_checkpoint(out / "checkpoint.pt")
    assert ck["config"]["arch"] == "official" and ck["step"] == STEPS
    assert tuned.state_dict().keys() == initial.state_dict().keys()
    rows = dataset_rows(out / "data")
    samples = val_samples(ShardedSource(out / "data", rows, "official"), tuned.cfg, len(rows), 0)
    assert len(samples) == len(SMALL_DEV)
    before, after = evaluate_loss(initial, samples, "cpu"), evaluate_loss(tuned, samples, "cpu")
    assert after < before - 0.005, (before, after)


def test_export_of_the_fine_tuned_model_runs_in_silkgen(run, silkgen, dev_dir, tmp_path):
    data, out = run
    assert (
        main(["export", "--checkpoint", str(out / "checkpoint.pt"), "--out", str(tmp_path / "model"), "--no-int8"]) == 0
    )
    meta = json.loads((tmp_path / "model" / "model.json").read_text())
    assert meta["arch"] == "official" and meta["model_version"] == 4 and meta["training"]["steps"] == STEPS
    r = subprocess.run(
        [
            str(silkgen),
            str(data / f"{SMALL_DEV[0]}.obj"),
            "--model",
            str(tmp_path / "model"),
            "--tokens",
            str(tmp_path / "ids.txt"),
            "--max-tokens",
            "40",
            "--seed",
            "1",
            "--threads",
            "1",
            "--stats",
            str(tmp_path / "stats.json"),
            "-q",
        ],
        capture_output=True,
        text=True,
        timeout=300,
    )
    assert r.returncode == 0, r.stderr
    ids = np.loadtxt(tmp_path / "ids.txt", dtype=np.int64, ndmin=1)
    assert 0 < ids.size <= 40 and ids.max() <= 10267
    assert json.loads((tmp_path / "stats.json").read_text())["tokens"] == ids.size
