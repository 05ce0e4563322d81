# SPDX-License-Identifier: MIT
"""`silk-export export --kv-variants ... --kv-precision ...`: which contract v4 cache variants an
export writes and which cache the folder uses by default (how the bundled model's folder is made
within its size limit, scripts/train_default_model.sh); a default without its variant is refused
before anything is written."""

from __future__ import annotations

import json
import subprocess
from pathlib import Path

import pytest
from test_json_valid import tiny_checkpoint

from silk_export.cli import main

KNOT = Path(__file__).resolve().parents[2] / "samples" / "torus_knot.obj"


def test_export_writes_only_the_chosen_variants_and_the_default(tmp_path, silkgen):
    tiny_checkpoint(tmp_path / "checkpoint.pt", {})
    out = tmp_path / "model"
    args = ["export", "--checkpoint", str(tmp_path / "checkpoint.pt"), "--out", str(out)]
    assert main(args + ["--kv-variants", "fp16", "--kv-precision", "fp16"]) == 0
    assert sorted(p.name for p in out.iterdir()) == [
        "decoder.int8.kv16.onnx",
        "decoder.int8.onnx",
        "decoder.kv16.onnx",
        "decoder.onnx",
        "encoder.onnx",
        "model.json",
    ]
    meta = json.loads((out / "model.json").read_text())
    assert meta["model_version"] == 4
    assert meta["files"] == {
        "encoder": "encoder.onnx",
        "decoder": "decoder.onnx",
        "decoder_int8": "decoder.int8.onnx",
        "kv_fp16": {"decoder": "decoder.kv16.onnx", "decoder_int8": "decoder.int8.kv16.onnx"},
        "default_kv_precision": "fp16",
    }
    # libsilk takes the folder as written: a plain run uses the fp16 cache in contract v4, with rows.
    stats = tmp_path / "stats.json"
    run = subprocess.run(
        [str(silkgen), str(KNOT), "-o", str(tmp_path / "knot.obj"), "--model", str(out), "--threads", "1"]
        + ["--max-tokens", "20", "--candidates", "2", "--stats", str(stats)],
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert stats.exists(), run.stderr
    report = json.loads(stats.read_text())
    assert (report["kv_precision"], report["decoder_contract"], report["rows"]) == ("fp16", 4, 2)


@pytest.mark.parametrize(
    ("flags", "message"),
    [
        (["--kv-variants", "fp16", "--kv-precision", "int8"], "default KV precision 'int8' needs its cache variant"),
        (["--kv-variants", "int8", "--kv-precision", "fp16"], "default KV precision 'fp16' needs its cache variant"),
    ],
)
def test_export_refuses_a_default_cache_it_does_not_write(tmp_path, capsys, flags, message):
    tiny_checkpoint(tmp_path / "checkpoint.pt", {})
    out = tmp_path / "model"
    assert main(["export", "--checkpoint", str(tmp_path / "checkpoint.pt"), "--out", str(out)] + flags) == 2
    assert message in capsys.readouterr().err
    assert not out.exists()
