# SPDX-License-Identifier: MIT
"""libsilk's ai.silk CrossAttention op (a decoder layer's attention over the point cloud's K/V in
the fp16/int8-cache variants), run by Python's onnxruntime with libsilk registered: the rewrite
of the exported pattern (MatMul with the transposed key, Mul, Softmax, MatMul) gives what plain
onnxruntime computes from the original graph, with float16 cross inputs it gives the original's
result on the float16-rounded K/V, patterns that differ are left alone, and shapes that do not fit
are errors naming the node."""

from __future__ import annotations

import numpy as np
import pytest

onnx = pytest.importorskip("onnx")
ort = pytest.importorskip("onnxruntime")

from onnx import TensorProto, helper, numpy_helper  # noqa: E402

from silk_export.onnx.cross_attention import half_cross_inputs, to_cross_attention  # noqa: E402
from silk_export.onnx.decode import session  # noqa: E402

H, M, D = 4, 9, 16


def _pattern(path, scale=0.25, axis=-1, perm=(0, 1, 3, 2), extra_user=False):
    """q [1,H,T,D] attends over cross_key_0 / cross_value_0 [1,H,M,D] as the exporter writes it."""
    nodes = [
        helper.make_node("Constant", [], ["c"], value=numpy_helper.from_array(np.array(scale, np.float32))),
        helper.make_node("Transpose", ["cross_key_0"], ["kt"], perm=list(perm)),
        helper.make_node("MatMul", ["q", "kt"], ["s"]),
        helper.make_node("Mul", ["s", "c"], ["ss"]),
        helper.make_node("Softmax", ["ss"], ["p"], axis=axis),
        helper.make_node("MatMul", ["p", "cross_value_0"], ["out"], name="cross_pv"),
    ]
    outs = [helper.make_tensor_value_info("out", TensorProto.FLOAT, None)]
    if extra_user:  # the scores are also a graph output: the pattern must stay
        outs.append(helper.make_tensor_value_info("ss", TensorProto.FLOAT, None))
    ins = [
        helper.make_tensor_value_info("q", TensorProto.FLOAT, [1, H, "T", D]),
        helper.make_tensor_value_info("cross_key_0", TensorProto.FLOAT, [1, H, "M", D]),
        helper.make_tensor_value_info("cross_value_0", TensorProto.FLOAT, [1, H, "M", D]),
    ]
    m = helper.make_model(
        helper.make_graph(nodes, "g", ins, outs), opset_imports=[helper.make_opsetid("", 17)], ir_version=8
    )
    onnx.save(m, str(path))
    return path


def _inputs(T=3, rows=M, seed=0):
    r = np.random.default_rng(seed)
    return {
        "q": r.normal(size=(1, H, T, D)).astype(np.float32),
        "cross_key_0": r.normal(size=(1, H, rows, D)).astype(np.float32),
        "cross_value_0": r.normal(size=(1, H, rows, D)).astype(np.float32),
    }


def _rewrite(src, dst):
    m = onnx.load(str(src))
    n = to_cross_attention(m.graph)
    if n:
        m.opset_import.append(helper.make_opsetid("ai.silk", 1))
    onnx.save(m, str(dst))
    return n, m


@pytest.mark.parametrize("T,scale", [(1, 0.25), (3, 10.0), (5, 0.125)])
def test_rewrite_computes_what_onnxruntime_computes(tmp_path, T, scale):
    src = _pattern(tmp_path / "a.onnx", scale)
    n, m = _rewrite(src, tmp_path / "b.onnx")
    assert n == 1 and [x.op_type for x in m.graph.node] == ["Constant", "CrossAttention"]
    x = _inputs(T)
    want = session(src).run(None, x)[0]
    got = session(tmp_path / "b.onnx").run(None, x)[0]
    assert got.shape == want.shape == (1, H, T, D)
    np.testing.assert_allclose(got, want, rtol=1e-5, atol=1e-5 * scale)


@pytest.mark.parametrize("T,scale", [(1, 10.0), (4, 0.25)])
def test_float16_cross_inputs_give_the_original_on_rounded_rows(tmp_path, T, scale):
    src = _pattern(tmp_path / "a.onnx", scale)
    m = onnx.load(str(src))
    to_cross_attention(m.graph)
    assert half_cross_inputs(m.graph) == 2
    assert [i.type.tensor_type.elem_type for i in m.graph.input] == [
        TensorProto.FLOAT,
        TensorProto.FLOAT16,
        TensorProto.FLOAT16,
    ]
    m.opset_import.append(helper.make_opsetid("ai.silk", 1))
    onnx.save(m, str(tmp_path / "h.onnx"))
    x = _inputs(T)
    rounded = {k: (v.astype(np.float16).astype(np.float32) if k.startswith("cross") else v) for k, v in x.items()}
    want = session(src).run(None, rounded)[0]
    got = session(tmp_path / "h.onnx").run(
        None, {k: (v.astype(np.float16) if k.startswith("cross") else v) for k, v in x.items()}
    )[0]
    np.testing.assert_allclose(got, want, rtol=1e-5, atol=1e-5 * scale)


def test_cross_inputs_read_by_anything_else_stay_float32(tmp_path):
    m = onnx.load(str(_pattern(tmp_path / "a.onnx", extra_user=True)))  # the pattern stays: MatMul reads them
    to_cross_attention(m.graph)
    assert half_cross_inputs(m.graph) == 0
    assert all(i.type.tensor_type.elem_type == TensorProto.FLOAT for i in m.graph.input)


@pytest.mark.parametrize("change", [dict(axis=2), dict(perm=(0, 1, 2, 3)), dict(extra_user=True)])
def test_other_patterns_are_left_alone(tmp_path, change):
    n, m = _rewrite(_pattern(tmp_path / "a.onnx", **change), tmp_path / "b.onnx")
    assert n == 0 and "CrossAttention" not in [x.op_type for x in m.graph.node]


def test_shapes_that_do_not_fit_are_refused_naming_the_node(tmp_path):
    _rewrite(_pattern(tmp_path / "a.onnx"), tmp_path / "b.onnx")
    s = session(tmp_path / "b.onnx")
    x = _inputs()
    x["cross_value_0"] = x["cross_value_0"][:, :, :5]
    with pytest.raises(
        Exception,
        match=r"CrossAttention 'cross_pv_cross': query \[1, 4, 3, 16\], key \[1, 4, 9, 16\] "
        r"and value \[1, 4, 5, 16\] do not fit",
    ):
        s.run(None, x)
    with pytest.raises(Exception, match="M >= 1"):
        s.run(None, _inputs(rows=0))


def _direct(path, source: bool):
    """One CrossAttention node: q [R,H,T,D], key/value [S,H,M,D] and, for contract v4, source [R]."""
    ins = [
        helper.make_tensor_value_info("q", TensorProto.FLOAT, ["R", H, "T", D]),
        helper.make_tensor_value_info("key", TensorProto.FLOAT, ["S", H, "M", D]),
        helper.make_tensor_value_info("value", TensorProto.FLOAT, ["S", H, "M", D]),
    ] + ([helper.make_tensor_value_info("source", TensorProto.INT32, ["R"])] if source else [])
    node = helper.make_node("CrossAttention", [i.name for i in ins], ["out"], name="cross", domain="ai.silk", scale=0.5)
    out = [helper.make_tensor_value_info("out", TensorProto.FLOAT, None)]
    g = helper.make_graph([node], "g", ins, out)
    ops = [helper.make_opsetid("", 17), helper.make_opsetid("ai.silk", 1)]
    onnx.save(helper.make_model(g, opset_imports=ops, ir_version=8), str(path))
    return session(path)


@pytest.mark.parametrize("sources,of_row", [(1, None), (4, None), (2, [1, 0, 1, 1])])
def test_batch_rows_are_bit_identical_to_each_row_alone(tmp_path, sources, of_row):
    """Contract v4: four rows reading cross K/V shared by all (S = 1), each its own (S = R), or of two
    meshes chosen by `source`: each row's output is that of the row alone with its own K/V."""
    r = np.random.default_rng(3)
    q = r.normal(size=(4, H, 2, D)).astype(np.float32)
    key, value = (r.normal(size=(sources, H, M, D)).astype(np.float32) for _ in range(2))
    x = {"q": q, "key": key, "value": value}
    if of_row is not None:
        x["source"] = np.array(of_row, np.int32)
    out = _direct(tmp_path / "b.onnx", of_row is not None).run(None, x)[0]
    alone = _direct(tmp_path / "a.onnx", False)
    for b in range(4):
        s = of_row[b] if of_row is not None else (0 if sources == 1 else b)
        one = alone.run(None, {"q": q[b : b + 1], "key": key[s : s + 1], "value": value[s : s + 1]})[0]
        np.testing.assert_array_equal(out[b : b + 1], one, err_msg=f"row {b}")


def test_batch_sources_that_do_not_fit_are_refused_naming_the_node(tmp_path):
    r = np.random.default_rng(4)
    q = r.normal(size=(2, H, 1, D)).astype(np.float32)
    kv = r.normal(size=(3, H, M, D)).astype(np.float32)
    with pytest.raises(Exception, match=r"CrossAttention 'cross': .*S = R or 1 \(or a source input\)"):
        _direct(tmp_path / "a.onnx", False).run(None, {"q": q, "key": kv, "value": kv})
    s = _direct(tmp_path / "b.onnx", True)
    with pytest.raises(Exception, match=r"CrossAttention 'cross': source\[1\] is 3, not one of the 3 key/value"):
        s.run(None, {"q": q, "key": kv, "value": kv, "source": np.array([0, 3], np.int32)})
    with pytest.raises(Exception, match=r"CrossAttention 'cross': source has shape \[3\], expected \[2\]"):
        s.run(None, {"q": q, "key": kv, "value": kv, "source": np.array([0, 1, 2], np.int32)})
