# SPDX-License-Identifier: MIT
"""ONNX export per docs/model_contract.md: names, shapes, dynamic axes, standard ops plus exactly
one com.microsoft GroupQueryAttention per layer, the model.json sidecar from the vocabulary
layout, and onnxruntime logits equal to PyTorch's (max abs diff <= 1e-4, fp32) on a
teacher-forced 64-token sequence: in one chunk, step by step through per-layer caches that are
shared between past_* and present_* (the runtime's way), and as prefix + chunk."""

from __future__ import annotations

import json

import numpy as np
import onnx
import onnxruntime as ort
import pytest
import torch

from silk_export.models.configs import get_config
from silk_export.models.silk_model import SilkModel
from silk_export.onnx.export import export_model
from silk_export.onnx.graphs import decoder_input_names, decoder_output_names
from silk_export.vocab import load_vocab

TOL = 1e-4


@pytest.fixture(scope="module")
def exported(tmp_path_factory, golden_dir):
    torch.manual_seed(0)
    torch.set_num_threads(1)
    model = SilkModel(get_config("micro")).eval()
    with torch.no_grad():  # break the init symmetry of the zero-initialised biases
        for p in model.parameters():
            p.add_(torch.randn_like(p) * 0.02)
    out = tmp_path_factory.mktemp("model")
    meta = export_model(model, out, {"steps": 0, "data": "test", "seed": 0}, int8=True)
    tokens = np.loadtxt(golden_dir / "torus.tokens.txt", dtype=np.int64)[:63]
    ids = torch.tensor([[model.bos_id] + tokens.tolist()])
    points = torch.randn(1, 4096, 6)
    with torch.no_grad():
        ref = model(ids, points).numpy()
    return model, out, meta, ids.numpy(), points.numpy(), ref


def session(path):
    so = ort.SessionOptions()
    so.intra_op_num_threads = 1
    return ort.InferenceSession(str(path), so, providers=["CPUExecutionProvider"])


def test_sidecar_follows_contract(exported):
    model, out, meta, *_ = exported
    v = load_vocab()
    on_disk = json.loads((out / "model.json").read_text())
    assert on_disk == meta
    assert meta["format"] == "silk-model" and meta["model_version"] == 4
    assert meta["token_format"] == v.layout["token_format"] and meta["token_format_version"] == 1
    assert meta["vocab"] == {
        "format_vocab_size": 10267,
        "eos_id": 10267,
        "pad_id": 10268,
        "bos_id": 10269,
        "model_vocab_size": 10269,
        "embedding_rows": 10270,
    }
    c = model.cfg
    assert meta["dims"] == {
        "d_model": c.d_model,
        "n_layers": c.n_layers,
        "n_heads": c.n_heads,
        "head_dim": c.head_dim,
        "n_latents": c.n_latents,
        "n_points": 4096,
        "max_seq_len": c.max_seq_len,
    }
    assert meta["arch"] == "silk"
    assert meta["files"] == {
        "encoder": "encoder.onnx",
        "decoder": "decoder.onnx",
        "decoder_int8": "decoder.int8.onnx",
        # contract v4 cache variants; the default stays the fp32 cache
        "kv_fp16": {"decoder": "decoder.kv16.onnx", "decoder_int8": "decoder.int8.kv16.onnx"},
        "kv_int8": {"decoder": "decoder.kv8.onnx", "decoder_int8": "decoder.int8.kv8.onnx"},
    }
    assert meta["normalize_bound"] == 0.95 and meta["config"] == "micro"
    assert "sampling" not in meta  # libsilk's built-in sampling defaults unless export is told otherwise


def test_sidecar_carries_chosen_sampling_defaults(exported):
    from silk_export.onnx.export import sidecar

    model, _, meta, *_ = exported
    chosen = {"temperature": 1.3, "top_k": 50}
    with_sampling = sidecar(model.cfg, meta["training"], meta["files"], {"sampling": chosen}, meta["model_version"])
    assert with_sampling["sampling"] == chosen
    assert {k: v for k, v in with_sampling.items() if k != "sampling"} == meta


def test_graph_interfaces_and_ops(exported):
    model, out, *_ = exported
    n = model.cfg.n_layers
    for name in ("encoder.onnx", "decoder.onnx"):
        m = onnx.load(str(out / name))
        onnx.checker.check_model(m)
        assert max(o.version for o in m.opset_import if o.domain in ("", "ai.onnx")) >= 17
        contrib = [node.op_type for node in m.graph.node if node.domain not in ("", "ai.onnx")]
        assert contrib == (["GroupQueryAttention"] * n if name == "decoder.onnx" else [])
        assert {node.domain for node in m.graph.node} <= {"", "ai.onnx", "com.microsoft"}
    dec = session(out / "decoder.onnx")
    assert [i.name for i in dec.get_inputs()] == decoder_input_names(n)
    assert [o.name for o in dec.get_outputs()] == decoder_output_names(n)
    assert decoder_input_names(2)[4:] == [
        "past_key_0",
        "past_value_0",
        "past_key_1",
        "past_value_1",
        "cross_key_0",
        "cross_value_0",
        "cross_key_1",
        "cross_value_1",
    ]
    shapes = {i.name: i.shape for i in dec.get_inputs()}
    types = {i.name: i.type for i in dec.get_inputs()}
    c = model.cfg
    assert isinstance(shapes["input_ids"][1], str) and isinstance(shapes["past_key_0"][2], str)
    assert shapes["past_key_0"][::3] == [1, c.head_dim] and shapes["past_key_0"][1] == c.n_heads
    assert shapes["cross_value_0"] == [1, c.n_heads, c.n_latents, c.head_dim]
    assert shapes["seqlens_k"] == [1] and shapes["total_sequence_length"] == []
    assert [types[k] for k in ("input_ids", "positions", "seqlens_k", "total_sequence_length")] == [
        "tensor(int64)",
        "tensor(int64)",
        "tensor(int32)",
        "tensor(int32)",
    ]
    enc = session(out / "encoder.onnx")
    assert [i.name for i in enc.get_inputs()] == ["points"] and [o.name for o in enc.get_outputs()] == ["cross_kv"]


def cross_feeds(cross, n_layers):
    return {
        f"cross_{kv}_{l}": np.ascontiguousarray(cross[l, j][None])
        for l in range(n_layers)
        for j, kv in enumerate(("key", "value"))
    }


def run_decoder(dec, ids, first, past, cross):
    """Unshared mode: past = per-layer [1,H,P,D] arrays (K, V, K, V, ...) of exactly `first`
    positions; returns (logits, the caches grown to first + T positions)."""
    n_layers = len(past) // 2
    t = ids.shape[1]
    feeds = {
        "input_ids": ids,
        "positions": np.arange(first, first + t, dtype=np.int64)[None],
        "seqlens_k": np.array([first + t - 1], np.int32),
        "total_sequence_length": np.array(first + t, np.int32),
        **cross_feeds(cross, n_layers),
    }
    feeds.update({f"past_{kv}_{l}": past[2 * l + j] for l in range(n_layers) for j, kv in enumerate(("key", "value"))})
    outs = dec.run(None, feeds)
    return outs[0], outs[1:]


def run_shared(dec, ids, first, cache, cross):
    """Shared mode, as engine/runtime does it: cache [L,2,1,H,C,D]; each layer's past_* and
    present_* are bound to the same block, the new rows land at first..first+T-1."""
    n_layers, _, _, h, cap, d = cache.shape
    t = ids.shape[1]
    b = dec.io_binding()
    b.bind_cpu_input("input_ids", np.ascontiguousarray(ids))
    b.bind_cpu_input("positions", np.arange(first, first + t, dtype=np.int64)[None])
    b.bind_cpu_input("seqlens_k", np.array([first + t - 1], np.int32))
    b.bind_cpu_input("total_sequence_length", np.array(first + t, np.int32))
    for name, value in cross_feeds(cross, n_layers).items():
        b.bind_cpu_input(name, value)
    for l in range(n_layers):
        for j, kv in enumerate(("key", "value")):
            ptr = cache[l, j].ctypes.data
            b.bind_input(f"past_{kv}_{l}", "cpu", 0, np.float32, [1, h, cap, d], ptr)
            b.bind_output(f"present_{kv}_{l}", "cpu", 0, np.float32, [1, h, cap, d], ptr)
    logits = np.zeros((1, t, 10269), np.float32)
    b.bind_output("logits", "cpu", 0, np.float32, list(logits.shape), logits.ctypes.data)
    dec.run_with_iobinding(b)
    return logits


def empty_past(c):
    return [np.zeros((1, c.n_heads, 0, c.head_dim), np.float32) for _ in range(2 * c.n_layers)]


def test_parity_one_chunk_and_stepwise(exported):
    model, out, _, ids, points, ref = exported
    c = model.cfg
    cross = session(out / "encoder.onnx").run(None, {"points": points})[0]
    assert cross.shape == (c.n_layers, 2, c.n_heads, c.n_latents, c.head_dim)
    dec = session(out / "decoder.onnx")
    logits, grown = run_decoder(dec, ids, 0, empty_past(c), cross)
    assert logits.shape == (1, 64, 10269) and grown[0].shape == (1, c.n_heads, 64, c.head_dim)
    assert np.abs(logits - ref).max() <= TOL
    # Shared buffers, capacity 80 > 64 filled with NaN: rows past the prefix must never be read.
    cache = np.full((c.n_layers, 2, 1, c.n_heads, 80, c.head_dim), np.nan, np.float32)
    worst, first = 0.0, 0
    for t in (1, 1, 2, 1, 7, 1, 1, 16, 1, 33):  # single steps and chunks, 64 in all
        lg = run_shared(dec, ids[:, first : first + t], first, cache, cross)
        worst = max(worst, float(np.abs(lg[0] - ref[0, first : first + t]).max()))
        first += t
    assert first == 64 and worst <= TOL
    for l in range(c.n_layers):  # the shared cache = the one-chunk run's present_*
        for j in range(2):
            np.testing.assert_allclose(cache[l, j, :, :, :64], grown[2 * l + j], atol=TOL)
    assert np.isnan(cache[:, :, :, :, 64:]).all()
    lg1, kv1 = run_decoder(dec, ids[:, :40], 0, empty_past(c), cross)  # prefix + chunk, unshared
    lg2, _ = run_decoder(dec, ids[:, 40:], 40, kv1, cross)
    assert np.abs(np.concatenate([lg1, lg2], axis=1) - ref).max() <= TOL


def test_int8_decoder_runs_and_stays_close(exported):
    model, out, _, ids, points, ref = exported
    c = model.cfg
    assert (out / "decoder.int8.onnx").stat().st_size < (out / "decoder.onnx").stat().st_size
    cross = session(out / "encoder.onnx").run(None, {"points": points})[0]
    logits, _ = run_decoder(session(out / "decoder.int8.onnx"), ids, 0, empty_past(c), cross)
    assert np.isfinite(logits).all()
    # one thread, 64 rows: the case where onnxruntime 1.22.1 miscomputes a 10269-wide
    # MatMulInteger (rows 31 and 63) unless the head stays fp32 (onnx_export.int8_unsafe_matmuls)
    assert np.abs(logits - ref).max() < 0.25  # quantization error, far below the logit spread
    assert float(np.corrcoef(logits.ravel(), ref.ravel())[0, 1]) > 0.99
    ops = {n.op_type for n in onnx.load(str(out / "decoder.int8.onnx")).graph.node}
    assert "MatMulInteger" in ops
