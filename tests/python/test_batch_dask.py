# SPDX-License-Identifier: MIT
"""silkgen --batch on a local Dask cluster (issue 21): a LocalCluster of 2 worker processes runs
`silkgen --batch LIST --shard i/2` for i = 0, 1, and the union of their reports covers the list
exactly once, every input ok. Skipped only when dask.distributed is not installed."""

from __future__ import annotations

import json
import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]


def run_shard(silkgen: str, lst: str, out: str, i: int, n: int) -> tuple[int, str, str]:
    """One shard on a worker: the command a farm would run, its exit status and its report."""
    report = f"{out}/report-{i}.jsonl"
    p = subprocess.run(
        [
            silkgen,
            "--batch",
            lst,
            "-o",
            out,
            "--shard",
            f"{i}/{n}",
            "--report",
            report,
            "--model",
            str(ROOT / "tests/models/tiny"),
            "--max-tokens",
            "120",
            "--threads",
            "1",
            "--candidates",
            "1",
            "--format",
            "obj",
            "-q",
        ],
        capture_output=True,
        text=True,
        timeout=600,
    )
    return p.returncode, report, p.stderr


def test_dask_local_cluster_covers_list_once(silkgen, shared, tmp_path):
    distributed = pytest.importorskip("dask.distributed")
    files = sorted((shared / "corpus/dev").glob("*.obj"))[:6] + [ROOT / "samples/torus_knot.obj"]
    lst = tmp_path / "list.txt"
    lst.write_text("".join(f"{f}\n" for f in files))
    out = tmp_path / "out"
    with (
        distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as cluster,
        distributed.Client(cluster) as client,
    ):
        futures = [client.submit(run_shard, str(silkgen), str(lst), str(out), i, 2, pure=False) for i in range(2)]
        results = client.gather(futures)
    seen = []
    for rc, report, stderr in results:
        assert rc == 0, stderr
        lines = [json.loads(line) for line in Path(report).read_text().splitlines()]
        assert all(r["status"] == "ok" and r["faces"] > 0 for r in lines), lines
        seen += [r["input"] for r in lines]
    assert sorted(seen) == sorted(str(f) for f in files)  # every input once, none twice
    assert sorted(p.name for p in out.glob("*.obj")) == sorted(f.stem + ".obj" for f in files)
