# SPDX-License-Identifier: MIT
"""`silk-export train` under torchrun (2 ranks, CPU gloo) gives the per-step losses of a single
process with the same global batch; checkpoints written by either resume to identical states;
an FSDP run resumes a DDP checkpoint and continues with the same losses."""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest
import torch

import silk_mesh
from silk_export.cli import main

EXPORT_DIR = Path(__file__).resolve().parents[1]
MESHES = ["cube", "octahedron", "tetrahedron", "torus_12x8", "two_components", "grid"]
STEPS = 20


def train_argv(data: Path, out: Path, *extra: str) -> list[str]:
    return [
        "train",
        "--data",
        str(data),
        "--config",
        "micro",
        "--steps",
        str(STEPS),
        "--out",
        str(out),
        "--batch-size",
        "4",
        "--threads",
        "1",
        "--log-every",
        "1",
        "--val-every",
        "0",
        "--no-progress",
        *extra,
    ]


def torchrun(argv: list[str]) -> None:
    env = {
        **os.environ,
        "SILK_LIBRARY": silk_mesh.library_path(),
        "OMP_NUM_THREADS": "1",
        "PYTHONPATH": str(EXPORT_DIR) + os.pathsep + os.environ.get("PYTHONPATH", ""),
    }
    cmd = [
        sys.executable,
        "-m",
        "torch.distributed.run",
        "--standalone",
        "--nproc_per_node",
        "2",
        "-m",
        "silk_export",
        *argv,
    ]
    r = subprocess.run(cmd, cwd=EXPORT_DIR, env=env, capture_output=True, text=True, timeout=600)
    assert r.returncode == 0, r.stdout[-3000:] + r.stderr[-3000:]


def losses(run: Path) -> list[float]:
    recs = [json.loads(x) for x in open(run / "log.jsonl")]
    assert [r["step"] for r in recs] == list(range(1, STEPS + 1))
    return [r["loss"] for r in recs]


def checkpoint(run: Path) -> dict:
    return torch.load(run / "checkpoint.pt", weights_only=False, map_location="cpu")


def assert_same_state(a: dict, b: dict) -> None:
    assert a["step"] == b["step"] == STEPS
    assert a["model"].keys() == b["model"].keys()
    for k in a["model"]:
        assert torch.equal(a["model"][k], b["model"][k]), k
    sa, sb = a["optimizer"]["state"], b["optimizer"]["state"]
    assert sa.keys() == sb.keys() and len(sa) > 0
    for k in sa:
        for x in ("exp_avg", "exp_avg_sq", "step"):
            assert torch.equal(sa[k][x], sb[k][x]), (k, x)


@pytest.fixture(scope="module")
def runs(golden_dir, tmp_path_factory, mesh_folder):
    data = mesh_folder(golden_dir, MESHES)
    d = tmp_path_factory.mktemp("runs")
    main(train_argv(data, d / "one"))  # single process, in this interpreter
    main(train_argv(data, d / "one_split", "--max-minutes", "1e-9"))  # stops after step 1
    first_one = checkpoint(d / "one_split")["step"]
    main(train_argv(data, d / "one_split"))  # resumes
    torchrun(train_argv(data, d / "two"))
    torchrun(train_argv(data, d / "two_split", "--max-minutes", "1e-9"))
    first_two = checkpoint(d / "two_split")["step"]
    shutil.copytree(d / "two_split", d / "fsdp_split")
    torchrun(train_argv(data, d / "two_split"))
    torchrun(train_argv(data, d / "fsdp_split", "--fsdp"))
    return d, first_one, first_two


def test_two_ranks_give_the_single_process_losses(runs):
    d, _, _ = runs
    one, two = losses(d / "one"), losses(d / "two")
    assert max(abs(x - y) for x, y in zip(one, two)) < 1e-4, (one, two)
    assert one[-1] < one[0] - 0.2  # it trains
    a, b = checkpoint(d / "one"), checkpoint(d / "two")
    assert a["world_size"] == 1 and b["world_size"] == 2 and a["model"].keys() == b["model"].keys()
    for k in a["model"]:
        torch.testing.assert_close(a["model"][k], b["model"][k], atol=1e-4, rtol=1e-3)


def test_resume_reproduces_the_uninterrupted_run_at_each_world_size(runs):
    d, first_one, first_two = runs
    assert first_one == first_two == 1
    assert losses(d / "one_split") == losses(d / "one")
    assert losses(d / "two_split") == losses(d / "two")
    assert_same_state(checkpoint(d / "one_split"), checkpoint(d / "one"))
    assert_same_state(checkpoint(d / "two_split"), checkpoint(d / "two"))


def test_fsdp_resumes_a_ddp_checkpoint_with_the_same_losses(runs):
    d, _, _ = runs
    two, fsdp = losses(d / "two"), losses(d / "fsdp_split")
    assert fsdp[0] == two[0]  # step 1 was run by DDP
    assert max(abs(x - y) for x, y in zip(two, fsdp)) < 1e-4, (two, fsdp)
    a, b = checkpoint(d / "two"), checkpoint(d / "fsdp_split")
    assert b["model"].keys() == a["model"].keys() and b["optimizer"]["state"].keys() == a["optimizer"]["state"].keys()
    for k in a["model"]:
        torch.testing.assert_close(a["model"][k], b["model"][k], atol=1e-4, rtol=1e-3)
