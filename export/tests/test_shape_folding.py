# SPDX-License-Identifier: MIT
"""Shape folding (silk_export.onnx.shape_folding): the decoder graph of every registered
architecture, in each weight precision, folded, computes exactly what it did for every chunk length and past length tried,
with its shape arithmetic gone; what the pass cannot prove (a Reshape with two unrelated dims, an
Expand whose consumer would broadcast differently, shapes behind an op it does not know) stays."""

from __future__ import annotations

import collections

import numpy as np
import pytest

onnx = pytest.importorskip("onnx")
ort = pytest.importorskip("onnxruntime")
from onnx import TensorProto, helper  # noqa: E402

from silk_export.registry import ARCHITECTURES  # noqa: E402
from silk_export.onnx.export import export_graphs, quantize_decoder, quantize_decoder_int4, transpose_linears  # noqa: E402
from silk_export.onnx.shape_folding import fold_shapes  # noqa: E402
from test_generate_architectures import tiny_model  # noqa: E402  (one tiny configuration per architecture)

SHAPE_OPS = {"Shape", "Gather", "Unsqueeze", "Concat", "Expand", "Cast"}


def _run(model, feeds: dict) -> list[np.ndarray]:
    so = ort.SessionOptions()
    so.log_severity_level = 3
    return ort.InferenceSession(model.SerializeToString(), so, providers=["CPUExecutionProvider"]).run(None, feeds)


def _decoder_feeds(graph, t: int, p: int, rng) -> dict:
    feeds = {
        "input_ids": rng.integers(0, 10267, (1, t)),
        "positions": np.arange(p, p + t)[None],
        "seqlens_k": np.array([p + t - 1], np.int32),
        "total_sequence_length": np.array(p + t, np.int32),
    }
    for i in graph.input:
        dims = [d.dim_value for d in i.type.tensor_type.shape.dim]
        if i.name.startswith("past_"):
            feeds[i.name] = rng.standard_normal([1, dims[1], p, dims[3]]).astype(np.float32)
        elif i.name.startswith("cross_"):
            feeds[i.name] = rng.standard_normal(dims).astype(np.float32)
    return feeds


@pytest.fixture(scope="module", params=sorted(ARCHITECTURES))
def exported(request, tmp_path_factory):
    """A tiny model's decoder in its three weight precisions (fp32, INT8 MatMulInteger, INT4 MatMulNBits)."""
    out = tmp_path_factory.mktemp(f"fold-{request.param}")
    export_graphs(transpose_linears(tiny_model(request.param)), out)
    quantize_decoder(out / "decoder.onnx", out / "decoder.int8.onnx")
    quantize_decoder_int4(out / "decoder.onnx", out / "decoder.int4.onnx")
    return out


@pytest.fixture(scope="module", params=["decoder", "decoder.int8", "decoder.int4"])
def decoder(exported, request):
    return onnx.load(str(exported / f"{request.param}.onnx"))


def test_folded_decoder_computes_the_same_bit_for_bit(decoder):
    folded = onnx.ModelProto()
    folded.CopyFrom(decoder)
    counts = fold_shapes(folded.graph)
    onnx.checker.check_model(folded)
    before = collections.Counter(n.op_type for n in decoder.graph.node)
    after = collections.Counter(n.op_type for n in folded.graph.node)
    assert after["Shape"] == 0 < before["Shape"]
    assert counts["removed"] == len(decoder.graph.node) - len(folded.graph.node) > 0
    computed = {o for n in folded.graph.node if n.op_type != "Constant" for o in n.output}
    for n in folded.graph.node:  # every shape, bound and expansion is now a constant
        if n.op_type in ("Reshape", "Slice", "Expand"):
            assert not set(n.input[1:]) & computed, n.name
    rng = np.random.default_rng(0)
    for t, p in [(1, 0), (1, 1), (1, 9), (4, 0), (3, 7)]:
        feeds = _decoder_feeds(decoder.graph, t, p, rng)
        for a, b in zip(_run(decoder, feeds), _run(folded, feeds)):
            assert a.shape == b.shape and np.array_equal(a, b), (t, p)


def _model(nodes, inputs, outputs, initializers=()):
    g = helper.make_graph(nodes, "g", inputs, outputs, list(initializers))
    return helper.make_model(g, opset_imports=[helper.make_opsetid("", 17)], ir_version=8)


def _shape_dims(name: str, data: str, indices: list[int]) -> list:
    """Nodes computing Concat(Shape(data)[i] for i in indices) into `name`."""
    nodes = [helper.make_node("Shape", [data], [f"{name}_s"])]
    for i in indices:
        nodes.append(
            helper.make_node(
                "Constant", [], [f"{name}_i{i}"], value=helper.make_tensor("v", TensorProto.INT64, [1], [i])
            )
        )
        nodes.append(helper.make_node("Gather", [f"{name}_s", f"{name}_i{i}"], [f"{name}_g{i}"], axis=0))
    nodes.append(helper.make_node("Concat", [f"{name}_g{i}" for i in indices], [name], axis=0))
    return nodes


def _float(name, dims):
    return helper.make_tensor_value_info(name, TensorProto.FLOAT, dims)


def test_reshape_targets_become_constants_only_where_proven():
    # x [A, B]: reshape to [A, B, 1] (A, B kept in place: 0, 0, 1) and to [B, A] (two dims that
    # are not the input's in place: not provable as a constant, stays computed).
    nodes = _shape_dims("keep", "x", [0, 1])
    nodes.append(helper.make_node("Constant", [], ["one"], value=helper.make_tensor("v", TensorProto.INT64, [1], [1])))
    nodes.append(helper.make_node("Concat", ["keep", "one"], ["keep3"], axis=0))
    nodes.append(helper.make_node("Reshape", ["x", "keep3"], ["y"]))
    nodes += _shape_dims("swap", "x", [1, 0])
    nodes.append(helper.make_node("Reshape", ["x", "swap"], ["z"]))
    m = _model(nodes, [_float("x", ["A", "B"])], [_float("y", None), _float("z", None)])
    folded = onnx.ModelProto()
    folded.CopyFrom(m)
    fold_shapes(folded.graph)
    reshapes = {n.output[0]: n for n in folded.graph.node if n.op_type == "Reshape"}
    init = {t.name: onnx.numpy_helper.to_array(t).tolist() for t in folded.graph.initializer}
    assert init[reshapes["y"].input[1]] == [0, 0, 1]
    assert reshapes["z"].input[1] == "swap"  # still computed from the shape
    for a, b in [(2, 3), (1, 5), (4, 1)]:
        x = np.arange(a * b, dtype=np.float32).reshape(a, b)
        for u, v in zip(_run(m, {"x": x}), _run(folded, {"x": x})):
            assert np.array_equal(u, v)


def test_expand_is_dropped_only_where_its_consumer_broadcasts_to_the_same_shape():
    # n [T, 1] expanded to y's shape [T, 4]: Div(y, .) gets n itself; Add(w [1, 4], .) would
    # broadcast n to [T, 4] only through the Expand, so that one stays.
    nodes = [
        helper.make_node("Shape", ["y"], ["ys"]),
        helper.make_node("Expand", ["n", "ys"], ["ne"]),
        helper.make_node("Div", ["y", "ne"], ["q"]),
        helper.make_node("Expand", ["n", "ys"], ["ne2"]),
        helper.make_node("Add", ["w", "ne2"], ["r"]),
    ]
    m = _model(
        nodes,
        [_float("y", ["T", 4]), _float("n", ["T", 1]), _float("w", [1, 4])],
        [_float("q", None), _float("r", None)],
    )
    folded = onnx.ModelProto()
    folded.CopyFrom(m)
    assert fold_shapes(folded.graph)["expands"] == 1
    ops = {n.output[0]: n for n in folded.graph.node}
    assert list(ops["q"].input) == ["y", "n"] and list(ops["r"].input) == ["w", "ne2"]
    rng = np.random.default_rng(1)
    for t in (1, 3):
        feeds = {
            "y": rng.standard_normal((t, 4)).astype(np.float32),
            "n": rng.random((t, 1)).astype(np.float32) + 1,
            "w": rng.standard_normal((1, 4)).astype(np.float32),
        }
        for u, v in zip(_run(m, feeds), _run(folded, feeds)):
            assert np.array_equal(u, v)


def test_an_unknown_op_ends_what_the_pass_can_follow():
    # u = Mystery(x): its shape is unknown, so the target computed from it stays computed.
    nodes = [helper.make_node("Mystery", ["x"], ["u"], domain="example.unknown")]
    nodes += _shape_dims("target", "u", [0, 1])
    nodes.append(helper.make_node("Reshape", ["u", "target"], ["y"]))
    m = _model(nodes, [_float("x", ["A", "B"])], [_float("y", None)])
    counts = fold_shapes(m.graph)
    assert counts == {"constants": 0, "expands": 0, "removed": 0}
    assert [n.op_type for n in m.graph.node].count("Shape") == 1


def test_constants_in_external_data_are_read_from_the_graphs_folder(decoder, tmp_path):
    # Quantizers save even the exporter's small int constants in the .data file (the release INT8 decoder).
    inline = onnx.ModelProto()
    inline.CopyFrom(decoder)
    want = fold_shapes(inline.graph)
    onnx.save(
        decoder,
        str(tmp_path / "d.onnx"),
        save_as_external_data=True,
        all_tensors_to_one_file=True,
        location="d.onnx.data",
        size_threshold=0,
        convert_attribute=True,
    )
    external = onnx.load(str(tmp_path / "d.onnx"), load_external_data=False)
    assert fold_shapes(external.graph, tmp_path) == want
    unread = onnx.load(str(tmp_path / "d.onnx"), load_external_data=False)
    assert fold_shapes(unread.graph)["constants"] < want["constants"]  # no folder: those stay computed


def test_a_graph_that_does_not_fit_its_shapes_is_left_as_it_is():
    # Transpose with a perm of the wrong length, Concat without its axis: not followed, no exception.
    nodes = [helper.make_node("Transpose", ["x"], ["t"], perm=[1, 0, 2])]
    nodes += _shape_dims("target", "t", [0, 1])
    nodes.append(helper.make_node("Reshape", ["t", "target"], ["y"]))
    nodes.append(helper.make_node("Concat", ["x", "x"], ["c"]))
    m = _model(nodes, [_float("x", ["A", "B"])], [_float("y", None), _float("c", None)])
    before = m.SerializeToString()
    assert fold_shapes(m.graph) == {"constants": 0, "expands": 0, "removed": 0}
    assert m.SerializeToString() == before


def test_an_initializer_that_is_also_an_input_is_no_constant():
    # IR < 4 style: "shape" is an initializer and a graph input, so a feed may replace it.
    nodes = [helper.make_node("Add", ["shape", "zero"], ["s2"]), helper.make_node("Reshape", ["x", "s2"], ["y"])]
    inits = [
        helper.make_tensor("shape", TensorProto.INT64, [2], [1, -1]),
        helper.make_tensor("zero", TensorProto.INT64, [1], [0]),
    ]
    m = _model(
        nodes,
        [_float("x", ["A", "B"]), helper.make_tensor_value_info("shape", TensorProto.INT64, [2])],
        [_float("y", None)],
        inits,
    )
    assert fold_shapes(m.graph)["constants"] == 0
