# SPDX-License-Identifier: MIT
"""The float16 logits head of the silk-form cache variants (half_logits.py, libsilk's ai.silk
HalfMatMul), run by Python's onnxruntime with libsilk registered: against the float16 weights'
product in numpy, the rewrite of the head only (MatMul + bias Add into `logits`, weight stored
inline or as external data), what it leaves alone, and the op's errors for shapes that do not fit."""

from __future__ import annotations

import numpy as np
import pytest

onnx = pytest.importorskip("onnx")
ort = pytest.importorskip("onnxruntime")

from onnx import TensorProto, helper, numpy_helper  # noqa: E402

from silk_export.onnx.decode import session  # noqa: E402
from silk_export.onnx.half_logits import to_half_logits  # noqa: E402


def _head(path, k, n, bias=True, external=False, other_user=False, seed=0):
    """x -> LayerNormalization-free toy decoder end: [hidden =] Relu(x); logits = hidden @ W (+ b)."""
    r = np.random.default_rng(seed)
    w = r.normal(0, 0.05, (k, n)).astype(np.float32)
    b = r.normal(0, 0.1, n).astype(np.float32)
    nodes = [
        helper.make_node("Relu", ["x"], ["hidden"], name="relu"),
        helper.make_node("MatMul", ["hidden", "W"], ["mm" if bias else "logits"], name="head"),
    ]
    inits = [numpy_helper.from_array(w, "W")]
    if bias:
        nodes.append(helper.make_node("Add", ["mm", "b"], ["logits"], name="bias"))
        inits.append(numpy_helper.from_array(b, "b"))
    outputs = [helper.make_tensor_value_info("logits", TensorProto.FLOAT, None)]
    if other_user:  # W read elsewhere too: it must stay
        nodes.append(helper.make_node("ReduceSum", ["W"], ["w_sum"], name="other", keepdims=0))
        outputs.append(helper.make_tensor_value_info("w_sum", TensorProto.FLOAT, None))
    g = helper.make_graph(
        nodes, "g", [helper.make_tensor_value_info("x", TensorProto.FLOAT, ["B", "T", k])], outputs, inits
    )
    m = helper.make_model(g, opset_imports=[helper.make_opsetid("", 17)], ir_version=8)
    if external:
        onnx.save(
            m,
            str(path),
            save_as_external_data=True,
            all_tensors_to_one_file=True,
            location=path.name + ".data",
            size_threshold=0,
        )
    else:
        onnx.save(m, str(path))
    return w, (b if bias else np.zeros(n, np.float32))


def _rewrite(src, dst):
    m = onnx.load(str(src), load_external_data=False)
    changed = to_half_logits(m.graph, src.parent)
    m.opset_import.append(helper.make_opsetid("ai.silk", 1))
    onnx.save(m, str(dst))
    return changed, m


@pytest.mark.parametrize("k,n,bias,external", [(96, 513, True, False), (40, 7, False, False), (64, 300, True, True)])
def test_head_becomes_halfmatmul_equal_to_the_float16_product(tmp_path, k, n, bias, external):
    w, b = _head(tmp_path / "d.onnx", k, n, bias, external)
    changed, m = _rewrite(tmp_path / "d.onnx", tmp_path / "h.onnx")
    assert changed
    ops = [(x.domain, x.op_type) for x in m.graph.node]
    assert ("ai.silk", "HalfMatMul") in ops and ("", "MatMul") not in ops
    assert [t.name for t in m.graph.initializer if t.name == "W"] == []  # the float32 weight is gone
    half = next(t for t in m.graph.initializer if t.name == "W__half")
    assert half.data_type == TensorProto.FLOAT16 and list(half.dims) == [n, k]
    x = np.random.default_rng(1).normal(size=(1, 3, k)).astype(np.float32)
    got = session(tmp_path / "h.onnx").run(None, {"x": x})[0]
    hidden = np.maximum(x, 0).astype(np.float64)
    want = hidden @ w.astype(np.float16).astype(np.float64) + b
    np.testing.assert_allclose(got, want, rtol=1e-5, atol=1e-5)
    full = hidden @ w.astype(np.float64) + b  # float32 weights: within the float16 rounding of each weight
    assert np.all(np.abs(got - full) <= (np.abs(hidden) @ np.abs(w).astype(np.float64)) * 2.0**-11 + 1e-5)


def test_a_weight_read_elsewhere_stays(tmp_path):
    _head(tmp_path / "d.onnx", 32, 16, other_user=True)
    changed, m = _rewrite(tmp_path / "d.onnx", tmp_path / "h.onnx")
    assert changed and {"W", "W__half"} <= {t.name for t in m.graph.initializer}


def test_graphs_without_such_a_head_are_left_unchanged(tmp_path):
    _head(tmp_path / "d.onnx", 32, 16)
    m = onnx.load(str(tmp_path / "d.onnx"))
    m.graph.node[1].input[1] = "x_weight"  # the weight is a graph input, not a constant
    m.graph.input.append(helper.make_tensor_value_info("x_weight", TensorProto.FLOAT, [32, 16]))
    before = m.SerializeToString()
    assert not to_half_logits(m.graph, tmp_path)
    assert m.SerializeToString() == before
    m2 = onnx.load(str(tmp_path / "d.onnx"))
    m2.graph.output[0].name = "scores"  # no `logits` output
    m2.graph.node[2].output[0] = "scores"
    before = m2.SerializeToString()
    assert not to_half_logits(m2.graph, tmp_path)
    assert m2.SerializeToString() == before


def test_op_names_shapes_that_do_not_fit(tmp_path):
    w = numpy_helper.from_array(np.zeros((5, 8), np.float16), "W")
    node = helper.make_node("HalfMatMul", ["a", "W"], ["y"], name="head", domain="ai.silk")
    g = helper.make_graph(
        [node],
        "g",
        [helper.make_tensor_value_info("a", TensorProto.FLOAT, None)],
        [helper.make_tensor_value_info("y", TensorProto.FLOAT, None)],
        [w],
    )
    m = helper.make_model(
        g, opset_imports=[helper.make_opsetid("", 17), helper.make_opsetid("ai.silk", 1)], ir_version=8
    )
    onnx.save(m, str(tmp_path / "bad.onnx"))
    s = session(tmp_path / "bad.onnx")
    assert s.run(None, {"a": np.ones((2, 8), np.float32)})[0].shape == (2, 5)
    with pytest.raises(Exception, match=r"HalfMatMul 'head': A has shape \[2, 7\], expected \[\.\.\., K\] with K = 8"):
        s.run(None, {"a": np.ones((2, 7), np.float32)})
