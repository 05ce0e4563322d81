# SPDX-License-Identifier: MIT
"""The "official" architecture against the official implementation's own outputs
(official-fixture/: random weights in the release's key layout): `silk-export import-official`
on the fixture, then the EXPORTED fp32 graphs run with onnxruntime must give the fixture's
conditioner output and teacher-forced logits within 1e-4 (one chunk and step by step through the
KV cache) and reproduce its 100 greedy ids. The contract-v3 facts of the folder are checked too."""

from __future__ import annotations

import json

import numpy as np
import onnx
import pytest
import torch

from silk_export.onnx import decode as onnx_decode
from silk_export.cli import main
from silk_export.official.checkpoint import load_official

TOL = 1e-4


@pytest.fixture(scope="module")
def fixture_dir(shared):
    d = shared / "official-fixture"
    if not (d / "model.safetensors").exists():
        pytest.skip(f"no official fixture in {d}")
    return d


@pytest.fixture(scope="module")
def imported(fixture_dir, tmp_path_factory):
    out = tmp_path_factory.mktemp("official") / "model"
    rc = main(
        [
            "import-official",
            str(fixture_dir / "model.safetensors"),
            "-o",
            str(out),
            "--precision",
            "fp32",
            "--config",
            str(fixture_dir / "config.json"),
            "--no-progress",
            "--fidelity-tokens",
            "4",
        ]
    )
    assert rc == 0
    return out


@pytest.fixture(scope="module")
def cross_kv(imported, fixture_dir):
    enc = onnx_decode.session(imported / "encoder.onnx")
    return enc.run(None, {"points": np.load(fixture_dir / "points.npy")[None]})[0]


@pytest.fixture(scope="module")
def decoder(imported):
    return onnx_decode.session(imported / "decoder.onnx")


def fixture_tokens(fixture_dir, name):
    return [int(x) for x in (fixture_dir / name).read_text().split()]


def test_model_json_is_contract_v4(imported):
    meta = json.loads((imported / "model.json").read_text())
    assert meta["model_version"] == 4 and meta["arch"] == "official"
    for key in ("kv_fp16", "kv_int8"):  # the cache variants take R rows (new_positions, cross_source)
        for name in meta["files"][key].values():
            inputs = [i.name for i in onnx.load(str(imported / name), load_external_data=False).graph.input]
            assert inputs[4:6] == ["new_positions", "cross_source"], name
    assert meta["dims"] == {
        "d_model": 32,
        "n_layers": 2,
        "n_heads": 2,
        "head_dim": 64,
        "n_latents": 261,
        "n_points": 4096,
        "max_seq_len": 513,
    }
    assert meta["preprocessing"]["kind"] == "official" and meta["preprocessing"]["surface_samples"] == 50000
    assert meta["sampling"] == {"temperature": 0.5, "top_k": 50, "top_p": 0.95, "top_p_temperature": 1.0}
    assert meta["files"]["default_decoder"] == "decoder" and "external_data" not in meta["files"]
    assert meta["import"]["load"]["used"] == 97 and meta["import"]["load"]["skipped_unused"] == 36
    assert meta["source"]["file"] == "model.safetensors" and len(meta["source"]["sha256"]) == 64
    assert "SHA-256" in (imported / "MODEL_CARD.md").read_text()


def test_graph_shapes_and_attention_scale(imported):
    enc = onnx.load(str(imported / "encoder.onnx"))
    dims = lambda v: [d.dim_value or d.dim_param for d in v.type.tensor_type.shape.dim]  # noqa: E731
    assert dims(enc.graph.input[0]) == [1, 4096, 6]  # v3: N fixed in the graph
    assert dims(enc.graph.output[0]) == [2, 2, 2, 261, 64]
    dec = onnx.load(str(imported / "decoder.onnx"))
    gqa = [n for n in dec.graph.node if n.op_type == "GroupQueryAttention"]
    assert len(gqa) == 2
    for n in gqa:
        assert {a.name: onnx.helper.get_attribute_value(a) for a in n.attribute}["scale"] == pytest.approx(10.0)


def test_context_matches_fixture(imported, fixture_dir, cross_kv):
    """The encoder graph's output is the per-layer cross K/V of the context; it must equal the K/V
    computed from the fixture's context.npy, and the re-implementation's context itself must match."""
    model, _ = load_official(fixture_dir / "model.safetensors", fixture_dir / "config.json", progress=False)
    ref_ctx = torch.from_numpy(np.load(fixture_dir / "context.npy"))[None]
    points = torch.from_numpy(np.load(fixture_dir / "points.npy"))[None]
    with torch.no_grad():
        assert np.abs(model.context(points)[0].numpy() - ref_ctx[0].numpy()).max() <= TOL
        ref_kv = np.stack(
            [torch.stack([k[0], v[0]]).numpy() for k, v in (layer.cross_kv(ref_ctx) for layer in model.layers)]
        )
    assert cross_kv.shape == ref_kv.shape == (2, 2, 2, 261, 64)
    assert np.abs(cross_kv - ref_kv).max() <= TOL
    keys = cross_kv[:, 0]
    assert np.allclose(np.linalg.norm(keys, axis=-1), 1.0, atol=1e-5)  # memory slots included


def test_teacher_forced_logits_one_chunk(fixture_dir, cross_kv, decoder):
    ids = [10269] + fixture_tokens(fixture_dir, "tokens.txt")
    ref = np.load(fixture_dir / "logits_teacher_forced.npy")
    got = onnx_decode.teacher_forced(decoder, cross_kv, ids)
    assert got.shape == ref.shape == (201, 10269)
    assert np.abs(got - ref).max() <= TOL


def test_teacher_forced_logits_step_by_step(fixture_dir, cross_kv, decoder):
    ids = [10269] + fixture_tokens(fixture_dir, "tokens.txt")
    ref = np.load(fixture_dir / "logits_teacher_forced.npy")
    state = onnx_decode.DecoderState(decoder, cross_kv)
    first = state.run(ids[:37])  # a prefix chunk, then one token per call
    rows = [first] + [state.run([t]) for t in ids[37:]]
    assert np.abs(np.concatenate(rows) - ref).max() <= TOL


def test_greedy_reproduces_official_loop(fixture_dir, cross_kv, decoder):
    want = fixture_tokens(fixture_dir, "greedy.txt")
    assert len(want) == 100 and -1 not in want
    assert onnx_decode.greedy(decoder, cross_kv, 10269, 10267, 100) == want


def test_external_data_export_is_the_same_network(fixture_dir, tmp_path):
    """The large-model path (weights streamed into decoder.onnx.data, never one big protobuf)
    gives the same logits, and the INT8 quantizer reads it."""
    from silk_export.onnx.export import export_graphs, quantize_decoder, transpose_linears

    model, _ = load_official(fixture_dir / "model.safetensors", fixture_dir / "config.json", progress=False)
    files = export_graphs(transpose_linears(model), tmp_path, external_over=0)
    assert files["external_data"] == ["decoder.onnx.data"] and (tmp_path / "decoder.onnx.data").exists()
    assert (tmp_path / "decoder.onnx").stat().st_size < 1 << 20
    assert sorted(p.name for p in tmp_path.iterdir()) == ["decoder.onnx", "decoder.onnx.data", "encoder.onnx"]
    points = np.load(fixture_dir / "points.npy")[None]
    cross = onnx_decode.session(tmp_path / "encoder.onnx").run(None, {"points": points})[0]
    ids = [10269] + fixture_tokens(fixture_dir, "tokens.txt")
    got = onnx_decode.teacher_forced(onnx_decode.session(tmp_path / "decoder.onnx"), cross, ids)
    assert np.abs(got - np.load(fixture_dir / "logits_teacher_forced.npy")).max() <= TOL
    quantize_decoder(tmp_path / "decoder.onnx", tmp_path / "decoder.int8.onnx")
    int8 = onnx_decode.teacher_forced(onnx_decode.session(tmp_path / "decoder.int8.onnx"), cross, ids)
    assert (int8.argmax(-1) == got.argmax(-1)).mean() >= 0.9
