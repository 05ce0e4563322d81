# SPDX-License-Identifier: MIT
"""libsilk's ai.silk Int4MatMul op (the INT4 weights of fp16- and int8-cache decoders), run by
Python's onnxruntime with libsilk registered: against onnxruntime's own MatMulNBits on the same
initializers, against the dequantized product in numpy, the rewrite of a graph's MatMulNBits
nodes (the ones it cannot compute are kept and named) and the errors for shapes that do not fit."""

from __future__ import annotations

import numpy as np
import pytest

onnx = pytest.importorskip("onnx")
ort = pytest.importorskip("onnxruntime")

from onnx import TensorProto, helper, numpy_helper  # noqa: E402

from silk_export.onnx.decode import session  # noqa: E402
from silk_export.onnx.int4_matmul import to_int4_matmul  # noqa: E402


def _weights(n, k, block, seed=0):
    r = np.random.default_rng(seed)
    packed = r.integers(0, 256, (n, k // block, block // 2), dtype=np.uint8)
    scales = r.uniform(0.001, 0.05, n * (k // block)).astype(np.float32)
    return packed, scales


def _dequantized(packed, scales, n, k, block):
    """w[n, k] = (nibble - 8) * scale: element 2i of a block in byte i's low nibble, 2i + 1 in its high one."""
    q = np.empty((n, k), np.float64)
    flat = packed.reshape(n, k // 2)
    q[:, 0::2], q[:, 1::2] = flat & 0x0F, flat >> 4
    return (q - 8) * np.repeat(scales.reshape(n, k // block).astype(np.float64), block, axis=1)


def _graph(path, n, k, block, packed, scales, op="MatMulNBits", domain="com.microsoft", rank=3, **extra):
    a_shape = ["B", "T", "K"][3 - rank :]
    attrs = dict(K=k, N=n, bits=4, block_size=block, **extra)
    node = helper.make_node(op, ["a", "w", "s"], ["y"], name="mm", domain=domain, **attrs)
    g = helper.make_graph(
        [node],
        "g",
        [helper.make_tensor_value_info("a", TensorProto.FLOAT, a_shape)],
        [helper.make_tensor_value_info("y", TensorProto.FLOAT, None)],
        [numpy_helper.from_array(packed, "w"), numpy_helper.from_array(scales, "s")],
    )
    m = helper.make_model(g, opset_imports=[helper.make_opsetid("", 17), helper.make_opsetid(domain, 1)], ir_version=8)
    onnx.save(m, str(path))
    return path


def _rewritten(src, dst):
    m = onnx.load(str(src))
    assert to_int4_matmul(m.graph) == (1, [])
    m.opset_import.append(helper.make_opsetid("ai.silk", 1))
    onnx.save(m, str(dst))
    return dst


@pytest.mark.parametrize(
    "n,k,block,lead", [(64, 256, 32, (1, 1)), (40, 96, 32, (1, 3)), (24, 512, 128, (2,)), (10, 128, 64, (1, 5))]
)
def test_matches_matmulnbits_and_the_dequantized_product(tmp_path, n, k, block, lead):
    packed, scales = _weights(n, k, block)
    ref = _graph(tmp_path / "ref.onnx", n, k, block, packed, scales, accuracy_level=4, rank=len(lead) + 1)
    silk = _rewritten(ref, tmp_path / "silk.onnx")
    a = np.random.default_rng(1).normal(size=lead + (k,)).astype(np.float32)
    got = session(silk).run(None, {"a": a})[0]
    want = session(ref).run(None, {"a": a})[0]
    assert got.shape == want.shape == a.shape[:-1] + (n,)
    if block == 32:  # accuracy level 4 quantizes the activations per block: the same groups, float rounding apart
        np.testing.assert_allclose(got, want, rtol=1e-5, atol=1e-5 * np.abs(want).max())
    else:  # onnxruntime's groups are the blocks, Int4MatMul's stay 32 wide: close, not equal
        np.testing.assert_allclose(got, want, rtol=0.05, atol=0.05 * np.abs(want).max())
    w = _dequantized(packed, scales, n, k, block)
    exact = a.astype(np.float64) @ w.T
    groups = np.abs(a.astype(np.float64)).reshape(a.shape[:-1] + (k // 32, 32)).max(-1)  # int8 grid per group of 32
    bound = (np.repeat(groups / 127 / 2, 32, axis=-1)) @ np.abs(w).T
    assert np.all(np.abs(got - exact) <= bound * 1.001 + 1e-5)


def test_rewrite_keeps_what_it_cannot_compute(tmp_path):
    packed, scales = _weights(8, 64, 32)
    m = onnx.load(str(_graph(tmp_path / "a.onnx", 8, 64, 32, packed, scales, accuracy_level=4)))
    node = m.graph.node[0]
    node.input.append("zero_points")
    assert to_int4_matmul(m.graph) == (0, ["mm: zero points, group index or bias inputs"])
    del node.input[3:]
    for a in node.attribute:
        if a.name == "block_size":
            a.i = 16
    assert to_int4_matmul(m.graph) == (0, ["mm: block_size=16"])
    for a in node.attribute:
        if a.name == "block_size":
            a.i = 32
        if a.name == "bits":
            a.i = 8
    assert to_int4_matmul(m.graph) == (0, ["mm: bits=8"])
    assert m.graph.node[0].op_type == "MatMulNBits"


def test_shapes_that_do_not_fit_are_refused_naming_the_node(tmp_path):
    packed, scales = _weights(8, 64, 32)
    bad_block = _graph(tmp_path / "b.onnx", 8, 64, 48, packed, scales, op="Int4MatMul", domain="ai.silk")
    with pytest.raises(Exception, match="Int4MatMul 'mm': block_size must be 32 or a multiple of 64"):
        session(bad_block).run(None, {"a": np.zeros((1, 1, 64), np.float32)})
    wrong_n = _graph(tmp_path / "n.onnx", 9, 64, 32, packed, scales, op="Int4MatMul", domain="ai.silk")
    with pytest.raises(Exception, match=r"Int4MatMul 'mm': B has shape \[8, 2, 16\], expected .* = \[9, 2, 16\]"):
        session(wrong_n).run(None, {"a": np.zeros((1, 1, 64), np.float32)})
    good = _graph(tmp_path / "g.onnx", 8, 64, 32, packed, scales, op="Int4MatMul", domain="ai.silk")
    with pytest.raises(Exception, match=r"Int4MatMul 'mm': A has shape \[1, 1, 32\], expected \[..., K\] with K = 64"):
        session(good).run(None, {"a": np.zeros((1, 1, 32), np.float32)})
    bits = _graph(tmp_path / "bits.onnx", 8, 64, 32, packed, scales, op="Int4MatMul", domain="ai.silk")
    m = onnx.load(str(bits))
    for a in m.graph.node[0].attribute:
        if a.name == "bits":
            a.i = 3
    onnx.save(m, str(bits))
    with pytest.raises(Exception, match="Int4MatMul 'mm': bits is 3; only 4 is implemented"):
        session(bits).run(None, {"a": np.zeros((1, 1, 64), np.float32)})
