# SPDX-License-Identifier: MIT
"""The ai.silk Int4MatMul form of a decoder's INT4 weights (docs/model_contract.md, "INT4 weights").
onnxruntime 1.22's com.microsoft MatMulNBits (bits 4, accuracy level 4) streams the release
decoder's 283 MB of 4-bit weights at about two thirds of a 2-core machine's read bandwidth for one
row of activations; libsilk's Int4MatMul takes the same inputs, attributes and initializers (no
weight is moved or copied) and reads them at memory speed. The fp16 and int8 cache variants, which
run in libsilk (or in Python's onnxruntime with libsilk registered), use it; the fp32-cache
decoder files keep MatMulNBits and run in any onnxruntime."""

from __future__ import annotations

from .silk_ops import SILK_DOMAIN, SILK_INT4

INT4_FORMS = ("silk", "ort")
_KEPT = {"K", "N", "bits", "block_size"}


def int4_unsupported(node) -> str | None:
    """Why MatMulNBits `node` has no Int4MatMul form (None when it has): Int4MatMul computes bits 4
    without zero points, group index or bias, block_size 32 or a multiple of 64, K a multiple of
    block_size."""
    from onnx import helper

    at = {a.name: helper.get_attribute_value(a) for a in node.attribute}
    k, n, bits, block = at.get("K", 0), at.get("N", 0), at.get("bits", 4), at.get("block_size", 0)
    if bits != 4:
        return f"bits={bits}"
    if len(node.input) > 3 and any(node.input[3:]):
        return "zero points, group index or bias inputs"
    if not (block == 32 or (block > 0 and block % 64 == 0)):
        return f"block_size={block}"
    if k <= 0 or n <= 0 or k % block:
        return f"K={k} with block_size={block}"
    return None


def to_int4_matmul(graph) -> tuple[int, list[str]]:
    """Rewrites, in place, every com.microsoft MatMulNBits node of `graph` that Int4MatMul computes
    into ai.silk Int4MatMul (accuracy_level dropped: its activations are always int8 in groups of
    32). Returns (nodes rewritten, "name: reason" for each node left as it was)."""
    rewritten, kept = 0, []
    for node in graph.node:
        if node.op_type != "MatMulNBits" or node.domain != "com.microsoft":
            continue
        why = int4_unsupported(node)
        if why:
            kept.append(f"{node.name}: {why}")
            continue
        attributes = [a for a in node.attribute if a.name in _KEPT]
        del node.attribute[:]
        node.attribute.extend(attributes)
        node.op_type, node.domain = SILK_INT4, SILK_DOMAIN
        rewritten += 1
    return rewritten, kept
