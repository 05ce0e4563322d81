#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""int4_matmul_bench: the release decoder's INT4 weight stream for one new position (24 layers x
six 1024x1024, one 1024->8192 and one 4096->1024 product; 283 MB at block 32, random weights),
as onnxruntime's com.microsoft MatMulNBits (accuracy level 4) and as libsilk's ai.silk
Int4MatMul over the same initializers, in one process: ms per call and GB/s for each, taking
turns, plus the largest relative difference of their outputs.

    python3 bench/int4_matmul_bench.py [--layers 24] [--calls 30] [--rounds 3] [--threads 2]

libsilk_ops is registered with onnxruntime for the ai.silk op (beside $SILK_LIBRARY or the build tree's
libsilk; $SILK_OPS_LIBRARY).
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPO / "export"))

import numpy as np  # noqa: E402

from silk_export.onnx.decode import silk_ops_library  # noqa: E402
from silk_export.onnx.int4_matmul import to_int4_matmul  # noqa: E402

SHAPES = [(1024, 1024)] * 6 + [(1024, 8192), (4096, 1024)]  # (K, N) per layer


def build(layers: int, seed: int = 0):
    from onnx import TensorProto, helper, numpy_helper

    rng, nodes, inits, outs = np.random.default_rng(seed), [], [], []
    for layer in range(layers):
        for j, (k, n) in enumerate(SHAPES):
            name = f"w{layer}_{j}"
            inits += [
                numpy_helper.from_array(rng.integers(0, 256, (n, k // 32, 16), dtype=np.uint8), name + "_q"),
                numpy_helper.from_array(rng.uniform(0.001, 0.02, n * k // 32).astype(np.float32), name + "_s"),
            ]
            nodes.append(
                helper.make_node(
                    "MatMulNBits",
                    [f"a{k}", name + "_q", name + "_s"],
                    [name + "_y"],
                    domain="com.microsoft",
                    K=k,
                    N=n,
                    bits=4,
                    block_size=32,
                    accuracy_level=4,
                )
            )
            outs.append(helper.make_tensor_value_info(name + "_y", TensorProto.FLOAT, None))
    ins = [helper.make_tensor_value_info(f"a{k}", TensorProto.FLOAT, [1, k]) for k in (1024, 4096)]
    model = helper.make_model(
        helper.make_graph(nodes, "int4", ins, outs, inits),
        ir_version=9,
        opset_imports=[helper.make_opsetid("", 17), helper.make_opsetid("com.microsoft", 1)],
    )
    weight_bytes = sum(t.ByteSize() for t in inits)
    return model, weight_bytes


def session(model, threads: int):
    import onnxruntime as ort

    so = ort.SessionOptions()
    so.intra_op_num_threads = threads
    so.register_custom_ops_library(silk_ops_library())
    return ort.InferenceSession(model.SerializeToString(), so, providers=["CPUExecutionProvider"])


def main() -> int:
    from onnx import helper

    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--layers", type=int, default=24)
    ap.add_argument("--calls", type=int, default=30)
    ap.add_argument("--rounds", type=int, default=3)
    ap.add_argument("--threads", type=int, default=2)
    a = ap.parse_args()
    ort_model, weight_bytes = build(a.layers)
    silk_model = type(ort_model)()
    silk_model.CopyFrom(ort_model)
    rewritten, kept = to_int4_matmul(silk_model.graph)
    assert rewritten == len(ort_model.graph.node) and not kept, kept
    silk_model.opset_import.append(helper.make_opsetid("ai.silk", 1))
    runs = {"MatMulNBits": session(ort_model, a.threads), "Int4MatMul": session(silk_model, a.threads)}
    rng = np.random.default_rng(1)
    feed = {f"a{k}": rng.standard_normal((1, k)).astype(np.float32) for k in (1024, 4096)}
    outs = {name: s.run(None, feed) for name, s in runs.items()}
    diff = max(float(np.abs(x - y).max() / np.abs(x).max()) for x, y in zip(outs["MatMulNBits"], outs["Int4MatMul"]))
    print(
        f"int4_matmul_bench: {a.layers} layers, {weight_bytes / 1e6:.0f} MB of weights per call, {a.threads} threads; "
        f"largest relative difference of the outputs {diff:.1e}"
    )
    for r in range(a.rounds):
        for name, s in runs.items():
            for _ in range(3):
                s.run(None, feed)
            t = time.perf_counter()
            for _ in range(a.calls):
                s.run(None, feed)
            dt = (time.perf_counter() - t) / a.calls
            print(f"  round {r + 1}  {name:12s} {dt * 1e3:6.2f} ms per call  {weight_bytes / dt / 1e9:5.1f} GB/s")
    return 0


if __name__ == "__main__":
    sys.exit(main())
