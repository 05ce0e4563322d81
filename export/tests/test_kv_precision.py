# SPDX-License-Identifier: MIT
"""The fp16 and int8 self-K/V cache variants (silk_export.onnx.kv_precision, `silk-export kv16`,
`kv8`): made by rewriting a decoder graph, they keep the weights (sharing external data), take
float16 caches / int8 rows [1, H, C, D + 4] and give the fp32 graph's logits to that precision."""

from __future__ import annotations

import json
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

onnx = pytest.importorskip("onnx")
pytest.importorskip("onnxruntime")

from silk_export.onnx.decode import DecoderState, session  # noqa: E402
from silk_export.onnx.kv_precision import add_kv16_to_folder, make_kv16_decoder, make_kv_decoder  # noqa: E402

REPO = Path(__file__).resolve().parents[2]
TINY = REPO / "tests" / "models" / "tiny"
IDS = [10269, 0, 5835, 8758, 1, 6112, 9420, 220, 460, 5803, 8381, 352]


def _cross(folder: Path) -> np.ndarray:
    pts = np.random.default_rng(0).normal(size=(1, 256, 6)).astype(np.float32)
    return session(folder / "encoder.onnx").run(None, {"points": pts})[0]


def _logits(decoder_path: Path, cross: np.ndarray, chunk: int) -> np.ndarray:
    state = DecoderState(session(decoder_path), cross)
    rows = [state.run(IDS[i : i + chunk]) for i in range(0, len(IDS), chunk)]
    return np.concatenate(rows)


@pytest.mark.parametrize("attention", ["silk", "ort"])
def test_variant_takes_float16_caches_and_matches_fp32(tmp_path, attention):
    shutil.copytree(TINY, tmp_path / "m")
    m = tmp_path / "m"
    assert make_kv16_decoder(m / "decoder.onnx", m / "variant.onnx", attention) == []
    nodes = onnx.load(str(m / "variant.onnx")).graph.node
    layers = json.loads((m / "model.json").read_text())["dims"]["n_layers"]
    want = "CachedAttention" if attention == "silk" else "GroupQueryAttention"
    assert [n.op_type for n in nodes].count(want) == layers
    assert sum("_kv16_" in n.name for n in nodes) == (0 if attention == "silk" else 4 * layers)
    # The silk form also folds the shape arithmetic (shape_folding.py); the ort form keeps the graph as is.
    assert ("Shape" in {n.op_type for n in nodes}) == (attention == "ort")
    types = {i.name: i.type for i in session(m / "variant.onnx").get_inputs()}
    assert types["past_key_0"] == types["past_value_1"] == "tensor(float16)"
    # The silk form: float16 cross K/V (CrossAttention reads it) and logits head (HalfMatMul).
    assert (
        types["cross_key_0"]
        == types["cross_value_1"]
        == ("tensor(float16)" if attention == "silk" else "tensor(float)")
    )
    assert ("HalfMatMul" in {n.op_type for n in nodes}) == (attention == "silk")
    cross = _cross(m)
    ref, half = _logits(m / "decoder.onnx", cross, 1), _logits(m / "variant.onnx", cross, 1)
    assert 0 < np.abs(ref - half).max() < 0.05  # float16 rounding, and only that
    assert (ref.argmax(-1) == half.argmax(-1)).all()
    np.testing.assert_allclose(_logits(m / "variant.onnx", cross, 5), half, atol=1e-2)


def test_variant_shares_external_data(tmp_path):
    m = tmp_path / "m"
    shutil.copytree(TINY, m)
    g = onnx.load(str(m / "decoder.onnx"))
    onnx.save_model(
        g,
        str(m / "decoder.onnx"),
        save_as_external_data=True,
        all_tensors_to_one_file=True,
        location="decoder.onnx.data",
        size_threshold=0,
    )
    assert make_kv16_decoder(m / "decoder.onnx", m / "decoder.kv16.onnx") == ["decoder.onnx.data"]
    dims = json.loads((m / "model.json").read_text())["dims"]
    head = dims["d_model"] * 10269 * 2  # the float16 logits head, inline
    assert head < (m / "decoder.kv16.onnx").stat().st_size < head + 100_000  # no copy of the other weights
    assert not (m / "decoder.kv16.onnx.data").exists()
    cross = _cross(m)
    assert (
        _logits(m / "decoder.kv16.onnx", cross, 1).argmax(-1) == _logits(m / "decoder.onnx", cross, 1).argmax(-1)
    ).all()


def test_refuses_a_graph_without_group_query_attention(tmp_path):
    shutil.copy(TINY / "encoder.onnx", tmp_path / "encoder.onnx")
    with pytest.raises(ValueError, match="no com.microsoft GroupQueryAttention"):
        make_kv16_decoder(tmp_path / "encoder.onnx", tmp_path / "x.onnx")
    with pytest.raises(ValueError, match="must sit beside"):
        make_kv16_decoder(TINY / "decoder.onnx", tmp_path / "x.onnx")


def _tiny_without(tmp_path, graphs: list[str], keys: list[str]):
    """A copy of the tiny model without the given variant graphs and model.json files keys."""
    m = tmp_path / "m"
    shutil.copytree(TINY, m)
    for g in graphs:
        (m / g).unlink()
    meta = json.loads((m / "model.json").read_text())
    for k in keys:
        del meta["files"][k]
    (m / "model.json").write_text(json.dumps(meta))
    return m


def test_cli_adds_variants_and_default(tmp_path):
    m = _tiny_without(tmp_path, ["decoder.kv16.onnx"], ["kv_fp16", "kv_int8"])
    p = subprocess.run(
        [sys.executable, "-m", "silk_export", "kv16", str(m), "--default", "fp16"],
        capture_output=True,
        text=True,
        cwd=REPO / "export",
    )
    assert p.returncode == 0, p.stderr
    files = json.loads((m / "model.json").read_text())["files"]
    assert files["kv_fp16"] == {"decoder": "decoder.kv16.onnx"} and files["default_kv_precision"] == "fp16"
    assert (m / "decoder.kv16.onnx").exists()
    with pytest.raises(ValueError, match="expected one of"):
        add_kv16_to_folder(m, "bf16")
    with pytest.raises(ValueError, match="needs files.kv_int8.decoder"):  # no kv8 variant yet
        add_kv16_to_folder(m, "int8")


def test_int8_variant_takes_int8_row_caches_and_matches_fp32(tmp_path):
    m = tmp_path / "m"
    shutil.copytree(TINY, m)
    assert make_kv_decoder(m / "decoder.onnx", m / "v8.onnx", "int8") == []
    meta = json.loads((m / "model.json").read_text())
    layers, heads, d = (meta["dims"][k] for k in ("n_layers", "n_heads", "head_dim"))
    assert [n.op_type for n in onnx.load(str(m / "v8.onnx")).graph.node].count("CachedAttention") == layers
    s = session(m / "v8.onnx")
    types = {i.name: (i.type, i.shape) for i in s.get_inputs()}
    assert types["past_key_0"][0] == types["past_value_1"][0] == "tensor(int8)"
    assert types["past_key_0"][1][1] == heads and types["past_key_0"][1][3] == d + 4
    assert {o.name: o.shape for o in s.get_outputs()}["present_value_1"][3] == d + 4
    assert types["cross_key_0"][0] == "tensor(float16)"
    cross = _cross(m)
    state = DecoderState(s, cross)
    q8 = np.concatenate([state.run([i]) for i in IDS])
    assert state.past[0].shape == (1, heads, len(IDS), d + 4) and state.past[0].dtype == np.int8
    ref = _logits(m / "decoder.onnx", cross, 1)
    assert 0 < np.abs(ref - q8).max() < 0.1  # int8 rounding of the cache (tiny model: 0.013)
    assert (ref.argmax(-1) == q8.argmax(-1)).all()
    np.testing.assert_allclose(_logits(m / "v8.onnx", cross, 5), q8, atol=1e-4)  # chunked = step-wise
    np.testing.assert_array_equal(_logits(TINY / "decoder.kv8.onnx", cross, 1), q8)  # the committed variant
    with pytest.raises(ValueError, match="only in the silk attention form"):
        make_kv_decoder(m / "decoder.onnx", m / "x.onnx", "int8", "ort")


def test_cli_kv8_adds_int8_variants_and_default(tmp_path):
    m = _tiny_without(tmp_path, ["decoder.kv8.onnx"], ["kv_int8"])
    p = subprocess.run(
        [sys.executable, "-m", "silk_export", "kv8", str(m), "--default", "int8"],
        capture_output=True,
        text=True,
        cwd=REPO / "export",
    )
    assert p.returncode == 0, p.stderr
    assert json.loads(p.stdout) == {"kv_int8": {"decoder": "decoder.kv8.onnx"}, "default_kv_precision": "int8"}
    files = json.loads((m / "model.json").read_text())["files"]
    assert files["kv_int8"] == {"decoder": "decoder.kv8.onnx"} and files["default_kv_precision"] == "int8"
    assert files["kv_fp16"] == {"decoder": "decoder.kv16.onnx"}  # the fp16 variant stays
    assert (m / "decoder.kv8.onnx").read_bytes() == (TINY / "decoder.kv8.onnx").read_bytes()
    p = subprocess.run(
        [sys.executable, "-m", "silk_export", "kv16", str(m), "--default", "int8"],
        capture_output=True,
        text=True,
        cwd=REPO / "export",
    )  # kv8 variants now exist
    assert p.returncode == 0, p.stderr
    meta = json.loads((m / "model.json").read_text())
    del meta["files"]["kv_int8"]
    (m / "model.json").write_text(json.dumps(meta))
    p = subprocess.run(
        [sys.executable, "-m", "silk_export", "kv16", str(m), "--default", "int8"],
        capture_output=True,
        text=True,
        cwd=REPO / "export",
    )
    assert p.returncode == 2 and "silk-export kv16: error" in p.stderr and "silk-export kv8 first" in p.stderr


def test_the_exported_precisions_are_libsilks_names():
    """The precisions the exporter writes (and silk-export's --kv-precision choices) are spelled as
    libsilk spells silk_kv_precision, "default" (the model's) aside: one spelling, libsilk's."""
    import silk_mesh

    from silk_export.onnx.kv_precision import KV_PRECISIONS

    libsilk = set(silk_mesh.enum_names("kv_precision")) - {"default"}
    assert set(KV_PRECISIONS) == libsilk, (KV_PRECISIONS, sorted(libsilk))
