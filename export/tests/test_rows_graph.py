# SPDX-License-Identifier: MIT
"""Decoder contract v4 graphs (silk_export.onnx.rows, make_kv_decoder(rows=True)) end to end: an
INT4 decoder of the official architecture, exported and rewritten into its fp16- and int8-cache v4
forms, run with three rows at different depths taking different counts of new positions against
two meshes in one call, gives each row exactly (bit for bit: logits and cache) what the row gives
run alone through the same graph, and a row alone gives what the contract v3 graph gives."""

from __future__ import annotations

import json
import shutil
import subprocess
from pathlib import Path

import numpy as np
import pytest

import silk_mesh

onnx = pytest.importorskip("onnx")
pytest.importorskip("onnxruntime")

from silk_export.onnx.decode import DecoderState, session  # noqa: E402
from silk_export.onnx.export import export_graphs, quantize_decoder_int4, sidecar  # noqa: E402
from silk_export.onnx.kv_precision import add_kv_to_folder, make_kv_decoder  # noqa: E402
from silk_export.onnx.rows import CROSS_SOURCE, NEW_POSITIONS  # noqa: E402

from test_generate_architectures import random_points, tiny_model  # noqa: E402

PAD = 10268
# Three rows: (ids already in its cache, ids it takes this call); depths 0, 5 and 9, taking 1, 3 and 2.
ROWS = [
    ([], [10269]),
    ([10269, 0, 5835, 8758, 1], [6112, 9420, 220]),
    ([10269, 3, 250, 700, 5700, 6200, 9000, 40, 4000], [460, 5803]),
]
SOURCE = [1, 0, 1]  # the mesh each row attends to


@pytest.fixture(scope="module")
def folder(tmp_path_factory):
    model = tiny_model("official")
    out = tmp_path_factory.mktemp("rows")
    export_graphs(model, out)
    quantize_decoder_int4(out / "decoder.onnx", out / "decoder.int4.onnx")
    encoder = session(out / "encoder.onnx")
    meshes = []
    for seed in (0, 1):
        pts = random_points(model.cfg)
        pts[:, :3] += seed  # two different point clouds
        meshes.append(encoder.run(None, {"points": pts[None]})[0])
    return out, meshes


def _feeds(graph, ids, pasts, news, past, cross, source):
    """Inputs for rows with ids [R, T] (padded), per-row depths/new counts, caches [R,...] and cross [S,...]."""
    layers = len(past) // 2
    feeds = {
        "input_ids": ids,
        "positions": np.array([[p + i if i < n else 0 for i in range(ids.shape[1])] for p, n in zip(pasts, news)]),
        "seqlens_k": np.array([p + n - 1 for p, n in zip(pasts, news)], np.int32),
        "total_sequence_length": np.array(max(p + n for p, n in zip(pasts, news)), np.int32),
    }
    if NEW_POSITIONS in {i.name for i in graph.get_inputs()}:
        feeds[NEW_POSITIONS] = np.array(news, np.int32)
        feeds[CROSS_SOURCE] = np.array(source, np.int32)
    for l in range(layers):
        feeds[f"past_key_{l}"], feeds[f"past_value_{l}"] = past[2 * l], past[2 * l + 1]
        feeds[f"cross_key_{l}"], feeds[f"cross_value_{l}"] = cross[2 * l], cross[2 * l + 1]
    return feeds


def _cross(graph, meshes):
    """cross_* [S, H, M, D] in the graph's type from each mesh's encoder output [L, 2, H, M, D]."""
    dtype = (
        np.float16 if {i.name: i.type for i in graph.get_inputs()}["cross_key_0"] == "tensor(float16)" else np.float32
    )
    return [np.stack([m[l, kv] for m in meshes]).astype(dtype) for l in range(meshes[0].shape[0]) for kv in (0, 1)]


def _alone(graph, meshes, done, new):
    """One row run alone from an empty cache: its earlier ids, then `new` (two calls). Returns
    (logits [T, V], cache list [H, P + T, D'] per layer and K/V, the cache before this call)."""
    inputs = {i.name: i for i in graph.get_inputs()}
    h, row = inputs["past_key_0"].shape[1], inputs["past_key_0"].shape[3]
    dtype = {"tensor(float16)": np.float16, "tensor(int8)": np.int8}[inputs["past_key_0"].type]
    cross = _cross(graph, meshes)
    past = [np.zeros((1, h, 0, row), dtype) for _ in cross]
    if done:
        out = graph.run(None, _feeds(graph, np.array([done]), [0], [len(done)], past, cross, [0]))
        past = out[1:]
    out = graph.run(None, _feeds(graph, np.array([new]), [len(done)], [len(new)], past, cross, [0]))
    return out[0][0], [c[0] for c in out[1:]], [c[0] for c in past]


@pytest.mark.parametrize("precision", ["fp16", "int8"])
def test_each_row_of_a_batch_is_the_row_alone_bit_for_bit(folder, precision):
    out, meshes = folder
    path = out / f"decoder.int4.v4.{precision}.onnx"
    make_kv_decoder(out / "decoder.int4.onnx", path, precision, rows=True)
    kinds = [n.op_type for n in onnx.load(str(path)).graph.node]
    assert "Int4MatMul" in kinds and "MatMulNBits" not in kinds and "GroupQueryAttention" not in kinds
    graph = session(path)
    alone = [_alone(graph, [meshes[s]], done, new) for (done, new), s in zip(ROWS, SOURCE)]
    pasts, news = [len(d) for d, _ in ROWS], [len(n) for _, n in ROWS]
    t, c = max(news), max(pasts)
    ids = np.array([new + [PAD] * (t - len(new)) for _, new in ROWS])
    past = []
    for k in range(len(alone[0][2])):
        block = np.zeros(
            (len(ROWS),) + alone[0][2][k].shape[:1] + (c,) + alone[0][2][k].shape[2:], alone[0][2][k].dtype
        )
        for r, (_, _, before) in enumerate(alone):
            block[r, :, : pasts[r]] = before[k]
        past.append(block)
    batch = graph.run(None, _feeds(graph, ids, pasts, news, past, _cross(graph, meshes), SOURCE))
    for r, (logits, cache, _) in enumerate(alone):
        np.testing.assert_array_equal(batch[0][r, : news[r]], logits, err_msg=f"row {r} logits")
        for k, layer in enumerate(cache):
            np.testing.assert_array_equal(batch[1 + k][r, :, : pasts[r] + news[r]], layer, err_msg=f"row {r} cache {k}")
    assert len({batch[0][r, 0].tobytes() for r in range(3)}) == 3  # the rows differ


@pytest.mark.parametrize("precision", ["fp16", "int8"])
def test_one_row_is_the_contract_v3_graph(folder, precision):
    """R = 1 through the v4 graph gives the v3 graph's logits and cache bit for bit (the runtime's
    one-row case)."""
    out, meshes = folder
    v3, v4 = out / f"v3.{precision}.onnx", out / f"v4.{precision}.onnx"
    make_kv_decoder(out / "decoder.int4.onnx", v3, precision)
    make_kv_decoder(out / "decoder.int4.onnx", v4, precision, rows=True)
    kinds = [sorted(n.op_type for n in onnx.load(str(p)).graph.node) for p in (v3, v4)]
    assert kinds[1] == kinds[0]  # folded as far as v3: a symbolic R costs no node
    shapes = {i.name: i.shape for i in session(v4).get_inputs()}
    assert shapes["past_key_0"][0] == shapes["new_positions"][0] == "R" and shapes["cross_key_1"][0] == "S"
    done, new = ROWS[2]
    a, b = _alone(session(v3), meshes[:1], done, new), _alone(session(v4), meshes[:1], done, new)
    np.testing.assert_array_equal(a[0], b[0])
    for x, y in zip(a[1], b[1]):
        np.testing.assert_array_equal(x, y)
    ids = done + new  # the Python decoding loop (decode.py) feeds a v4 graph one row
    want = DecoderState(session(v3), meshes[0]).run(ids)
    np.testing.assert_array_equal(DecoderState(session(v4), meshes[0]).run(ids), want)


def test_refusals_name_the_graph(folder):
    out, _ = folder
    with pytest.raises(ValueError, match="only in the silk attention form"):
        make_kv_decoder(out / "decoder.int4.onnx", out / "x.onnx", "fp16", "ort", rows=True)
    make_kv_decoder(out / "decoder.int4.onnx", out / "v4.onnx", "fp16", rows=True)
    with pytest.raises(ValueError, match="v4.onnx: already a contract v4 graph"):
        from silk_export.onnx.rows import wire_rows

        wire_rows(onnx.load(str(out / "v4.onnx")).graph, out / "v4.onnx")


@pytest.mark.skipif(not silk_mesh.generation_available(), reason="libsilk without onnxruntime")
@pytest.mark.parametrize("precision", ["fp16", "int8"])
def test_libsilk_runs_a_v4_folder_with_one_row_as_the_v3_folder(folder, dev_dir, silkgen, precision, tmp_path):
    """model_version 4 with v4 cache variants loads in libsilk and, one row, gives the v3 folder's
    ids (INT4 decoder, sampled with a seed); the v3 folder keeps loading. silkgen --stats names the
    folder's model_version and its decoder's contract, and for v3 how to re-export it."""
    out, _ = folder
    ids = {}
    for version in (3, 4):
        m = tmp_path / f"v{version}"
        m.mkdir()
        for name in ("encoder.onnx", "decoder.onnx", "decoder.int4.onnx"):
            shutil.copy(out / name, m / name)
        meta = sidecar(tiny_model("official").cfg, {"steps": 0, "data": None, "seed": None}, {})
        meta["files"] = {"encoder": "encoder.onnx", "decoder": "decoder.onnx", "decoder_int4": "decoder.int4.onnx"}
        (m / "model.json").write_text(json.dumps(meta))
        add_kv_to_folder(m, precision, rows=version == 4)
        assert json.loads((m / "model.json").read_text())["model_version"] == version
        mesh = sorted(dev_dir.glob("*.obj"))[0]
        with silk_mesh.Model(m, threads=1, decoder="int4", kv_precision=precision) as model:
            with silk_mesh.Generator(model) as gen:
                ids[version] = list(gen.run(mesh, seed=4, max_tokens=60)[1])
        run = [silkgen, mesh, "--model", m, "--decoder", "int4", "--kv-precision", precision, "--seed", "4"]
        run += ["--max-tokens", "60", "-o", tmp_path / f"{version}.obj", "--stats", tmp_path / f"{version}.json"]
        subprocess.run([str(x) for x in run], check=True, capture_output=True)
        stats = json.loads((tmp_path / f"{version}.json").read_text())
        assert stats["model_version"] == stats["decoder_contract"] == version and stats["tokens"] == len(ids[version])
        note = "re-exports it as model_version 4"
        assert (note in stats.get("model_version_note", "")) == (version == 3), stats.get("model_version_note")
    assert len(ids[3]) > 10 and ids[4] == ids[3]


def test_kv_commands_keep_a_v4_folder_v4(folder, tmp_path):
    """silk-export kv16 / kv8 on a model_version 4 folder write v4 variants (no mixed contracts);
    on a v3 folder v3 ones unless asked; a v2 folder cannot take v4 variants."""
    out, _ = folder
    for version in (2, 3, 4):
        m = tmp_path / f"v{version}"
        m.mkdir()
        shutil.copy(out / "decoder.int4.onnx", m / "decoder.int4.onnx")
        shutil.copy(out / "decoder.onnx", m / "decoder.onnx")
        meta = sidecar(tiny_model("official").cfg, {"steps": 0, "data": None, "seed": None}, {}, None, version)
        meta["files"] = {"encoder": "encoder.onnx", "decoder": "decoder.onnx", "decoder_int4": "decoder.int4.onnx"}
        (m / "model.json").write_text(json.dumps(meta))
        if version == 2:
            with pytest.raises(ValueError, match="model_version 2: contract v4 needs a version 3 folder"):
                add_kv_to_folder(m, "fp16", rows=True)
            assert not (m / "decoder.kv16.onnx").exists()  # refused before writing
            continue
        add_kv_to_folder(m, "int8")
        inputs = [i.name for i in onnx.load(str(m / "decoder.int4.kv8.onnx")).graph.input]
        assert (NEW_POSITIONS in inputs) == (version == 4)
        assert json.loads((m / "model.json").read_text())["model_version"] == version


def test_int4_quantizes_only_whole_blocks(tmp_path):
    """quantize_decoder_int4 leaves fp32 every weight MatMul whose K is not a whole number of
    32-blocks (onnxruntime's MatMulNBits pads them, and on AVX2 without AVX-512 its batch rows
    differ from each row alone), and quantizes the others: the repository's tiny test model
    (d_model 16) has both kinds."""
    src_path = Path(__file__).resolve().parents[2] / "tests/models/tiny/decoder.onnx"
    quantize_decoder_int4(src_path, tmp_path / "decoder.int4.onnx")
    src = onnx.load(str(src_path))
    shapes = {i.name: list(i.dims) for i in src.graph.initializer}
    weights = [n for n in src.graph.node if n.op_type == "MatMul" and len(shapes.get(n.input[1], [])) == 2]
    ks = [shapes[n.input[1]][0] for n in weights]
    assert any(k % 32 for k in ks) and any(k % 32 == 0 for k in ks), ks
    q = onnx.load(str(tmp_path / "decoder.int4.onnx"))
    attrs = [{a.name: a.i for a in n.attribute} for n in q.graph.node if n.op_type == "MatMulNBits"]
    assert attrs and all(a["K"] % 32 == 0 for a in attrs)
    q_shapes = {i.name: list(i.dims) for i in q.graph.initializer}
    kept = [q_shapes[n.input[1]][0] for n in q.graph.node if n.op_type == "MatMul" and n.input[1] in q_shapes]
    assert sorted(k for k in kept if k % 32) == sorted(k for k in ks if k % 32)
