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
