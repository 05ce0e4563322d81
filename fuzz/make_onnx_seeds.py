#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Writes fuzz/corpus/onnx_external_data_fuzzer/: small ONNX models (needs the onnx package)
whose tensors use external data in every place the walker looks (initializer, sparse
initializer, Constant attribute, If subgraph, function), plus bad locations and a truncation.
Usage: fuzz/make_onnx_seeds.py"""

import pathlib

from onnx import TensorProto, helper
from onnx.external_data_helper import set_external_data

out = pathlib.Path(__file__).resolve().parent / "corpus" / "onnx_external_data_fuzzer"


def ext(name, location, dims=(2,)):
    t = helper.make_tensor(name, TensorProto.FLOAT, list(dims), bytes(4 * dims[0]), raw=True)
    set_external_data(t, location=location, offset=0, length=4 * dims[0])
    t.ClearField("raw_data")
    t.data_location = TensorProto.EXTERNAL
    return t


def model(location):
    x = helper.make_tensor_value_info("x", TensorProto.FLOAT, [2])
    y = helper.make_tensor_value_info("y", TensorProto.FLOAT, [2])
    const = helper.make_node("Constant", [], ["c"], value=ext("cv", location))
    then_g = helper.make_graph(
        [helper.make_node("Identity", ["c"], ["t"])],
        "then",
        [],
        [helper.make_tensor_value_info("t", TensorProto.FLOAT, [2])],
        [ext("ti", location)],
    )
    cond = helper.make_tensor("cond", TensorProto.BOOL, [], [True])
    if_node = helper.make_node("If", ["cond"], ["y"], then_branch=then_g, else_branch=then_g)
    sparse = helper.make_sparse_tensor(
        ext("sv", location, (1,)), helper.make_tensor("si", TensorProto.INT64, [1], [0]), [2]
    )
    g = helper.make_graph([const, if_node], "g", [x], [y], [ext("w", location), cond], sparse_initializer=[sparse])
    fn = helper.make_function(
        "local",
        "f",
        ["a"],
        ["b"],
        [helper.make_node("Constant", [], ["b"], value=ext("fv", location))],
        [helper.make_opsetid("", 17)],
    )
    return helper.make_model(
        g, functions=[fn], opset_imports=[helper.make_opsetid("", 17), helper.make_opsetid("local", 1)]
    )


out.mkdir(parents=True, exist_ok=True)
for name, loc in [
    ("inside", "decoder.onnx.data"),
    ("climbs_out", "../outside.bin"),
    ("absolute", "/etc/passwd"),
    ("subfolder", "w/d.bin"),
]:
    (out / f"{name}.onnx").write_bytes(model(loc).SerializeToString())
data = model("decoder.onnx.data").SerializeToString()
(out / "truncated.onnx").write_bytes(data[: len(data) // 2])
