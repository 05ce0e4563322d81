# SPDX-License-Identifier: MIT
"""Every JSON file the project writes is valid JSON (issue 20, finding 7): Python's json module
writes a bare NaN / Infinity unless told not to, and silkgen then reads "not a JSON object". Here:
the one JSON writer (silk_export.json_io) refuses or nulls them, `silk-export export` refuses a
checkpoint with non-finite weights, model.json refuses non-finite figures, and the C API's
reports (a candidate's Chamfer score of an empty mesh is +inf) parse with a strict parser."""

from __future__ import annotations

import json
import math

import pytest
from pathlib import Path
import torch

import silk_mesh
from silk_export.cli import main
from silk_export.json_io import NonFiniteJSONError, dumps, jsonl_line, write_json
from silk_export.checkpoint import save_state
from silk_export.models.configs import ModelConfig
from silk_export.registry import get_architecture

REPO_ROOT = Path(__file__).resolve().parents[2]  # this checkout (tests only)


def strict_loads(text: str):
    """json.loads that, like every non-Python reader, refuses NaN / Infinity / -Infinity."""

    def refuse(word):
        raise ValueError(f"not JSON: {word}")

    return json.loads(text, parse_constant=refuse)


DOC = {"a": {"b": [1.0, float("nan")], "c": float("inf")}, "d": -math.inf, "e": 2, "f": "NaN"}


def test_python_json_module_writes_invalid_json_by_default():
    with pytest.raises(ValueError, match="not JSON"):
        strict_loads(json.dumps(DOC))


def test_refuse_names_every_nonfinite_field(tmp_path):
    with pytest.raises(NonFiniteJSONError) as e:
        write_json(tmp_path / "model.json", DOC)
    msg = str(e.value)
    assert str(tmp_path / "model.json") in msg
    assert "'a.b[1]' = nan" in msg and "'a.c' = inf" in msg and "'d' = -inf" in msg
    assert not (tmp_path / "model.json").exists()


def test_null_writes_valid_json(tmp_path):
    want = {"a": {"b": [1.0, None], "c": None}, "d": None, "e": 2, "f": "NaN"}
    assert strict_loads(dumps(DOC, "null")) == want
    assert strict_loads(jsonl_line(DOC, "null")) == want and jsonl_line(DOC, "null").count("\n") == 1
    path = write_json(tmp_path / "r.json", DOC, "null")
    assert strict_loads(path.read_text()) == want and path.read_text().endswith("}\n")
    assert strict_loads(dumps({"x": 1.5, "y": [0.0, -2.0]})) == {"x": 1.5, "y": [0.0, -2.0]}
    with pytest.raises(ValueError, match="nonfinite 'zero'"):
        dumps(DOC, "zero")


TINY_SILK = ModelConfig(
    "tiny-silk", d_model=64, n_layers=2, n_heads=2, n_latents=16, max_seq_len=64, encoder_layers=1, n_points=128
)


def tiny_checkpoint(path, poison: dict):
    torch.manual_seed(0)
    model = get_architecture("silk").build(TINY_SILK)
    state = {k: v.clone() for k, v in model.state_dict().items()}
    for key, values in poison.items():
        state[key].view(-1)[: len(values)] = torch.tensor(values)
    save_state(path, model.cfg.to_dict(), state, None, 0, {})
    return sorted(state)


def test_export_refuses_nonfinite_weights(tmp_path, capsys):
    keys = [k for k in tiny_checkpoint(tmp_path / "probe.pt", {}) if k.endswith(".weight")]
    nan_key, inf_key = keys[0], keys[-1]
    tiny_checkpoint(tmp_path / "checkpoint.pt", {nan_key: [float("nan"), 0.5, float("nan")], inf_key: [float("-inf")]})
    out = tmp_path / "model"
    assert main(["export", "--checkpoint", str(tmp_path / "checkpoint.pt"), "--out", str(out), "--no-int8"]) == 2
    err = capsys.readouterr().err
    assert "silk-export export: error:" in err and "non-finite" in err
    assert f"key '{nan_key}': 2 NaN" in err and f"key '{inf_key}': 1 Inf" in err
    assert not out.exists()


def test_export_refuses_a_nonfinite_sampling_default(tmp_path, capsys):
    tiny_checkpoint(tmp_path / "checkpoint.pt", {})
    out = tmp_path / "model"
    assert (
        main(
            [
                "export",
                "--checkpoint",
                str(tmp_path / "checkpoint.pt"),
                "--out",
                str(out),
                "--no-int8",
                "--temperature",
                "nan",
            ]
        )
        == 2
    )
    assert "model.json" in (err := capsys.readouterr().err) and "'sampling.temperature' = nan" in err
    assert not out.exists()


TINY_MODEL = REPO_ROOT / "tests/models/tiny"
KNOT = REPO_ROOT / "samples/torus_knot.obj"


@pytest.mark.skipif(not silk_mesh.generation_available(), reason="libsilk without onnxruntime")
def test_capi_reports_are_strict_json():
    """A run's report and trace are strict JSON (no NaN/Infinity literal). The case with infinite
    Chamfer scores (a run without the grammar mask, no face) is checked in C++, where that mode is
    reachable: tests/capi/measurement_mode_test.cpp."""
    with (
        silk_mesh.Model(TINY_MODEL, threads=1) as model,
        silk_mesh.Generator(model) as gen,
        silk_mesh.Mesh.load(KNOT) as src,
    ):
        # report_flags 1 = SILK_GENERATE_RECORD_TRACE: report_json(trace=True) is available
        mesh, _, st = gen.run(src, seed=3, max_tokens=60, candidates=2, report_flags=1)
        mesh.close()
        report = strict_loads(gen.report_json())
        assert len(report["candidates"]) == 2 and report["faces"] == st["faces"]
        trace = strict_loads(gen.report_json(trace=True))
        assert len(trace["points"]) > 0 and all(isinstance(x, float) for x in trace["points"])


@pytest.mark.skipif(not silk_mesh.generation_available(), reason="libsilk without onnxruntime")
def test_the_measurement_switches_are_no_generate_parameters():
    """unconstrained and debug_flags left silk_generate_params (C API 1.0-1.3's measurement
    switches, now reserved slots): the binding refuses them by name instead of passing them on."""
    with silk_mesh.Model(TINY_MODEL, threads=1) as model, silk_mesh.Generator(model) as gen:
        for name in ("unconstrained", "debug_flags", "reserved"):
            with pytest.raises(TypeError, match=f"unknown parameter '{name}'"):
                gen.run(KNOT, max_tokens=14, **{name: 1})
