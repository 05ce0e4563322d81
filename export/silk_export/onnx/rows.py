# SPDX-License-Identifier: MIT
"""Decoder contract v4 (docs/model_contract.md, "Decoder contract v4: R rows per call"): one call
advances R sequences at their own depths, so every weight is read once for all rows. Made by
rewriting the silk form of a cache variant (kv_precision.py) instead of re-tracing: the batch dim
of input_ids, positions, logits and the caches becomes the symbol R (cross_* S, the meshes the rows
attend to) before the shape arithmetic is folded, so every folded Reshape target keeps it dynamic
(0 = the input's dim), and two int32 [R] inputs reach the libsilk kernels that take them:
`new_positions` (each row's count of new positions, CachedAttention's eighth input) and
`cross_source` (the cross K/V batch each row reads, CrossAttention's fourth input)."""

from __future__ import annotations

from .silk_ops import SILK_ATTENTION, SILK_CROSS, SILK_DOMAIN

ROWS_CONTRACT = 4  # model.json model_version of a folder whose decoders take R rows
NEW_POSITIONS, CROSS_SOURCE = "new_positions", "cross_source"
_ROW_NAMES = ("input_ids", "positions", "seqlens_k", "logits", "past_", "present_")


def _set_batch(vi, symbol: str) -> None:
    dims = vi.type.tensor_type.shape.dim
    if not dims:
        raise ValueError(f"'{vi.name}' has no shape: not a contract decoder graph")
    dims[0].Clear()
    dims[0].dim_param = symbol


def batch_dims(graph) -> None:
    """Makes dim 0 of the row inputs/outputs and of cross_* R, in place (call before fold_shapes,
    which then keeps it symbolic). cross_* are R while folding: the traced cross-attention's
    q·kᵀ broadcasts its batch against theirs, and with a second symbol the folding would lose
    track of R after it (and keep each layer's qk-norm Expand); wire_rows, after the rewrite into
    CrossAttention (which takes S against R), names them S."""
    for vi in list(graph.input) + list(graph.output):
        if vi.name.startswith(_ROW_NAMES) or vi.name.startswith("cross_"):
            _set_batch(vi, "R")


def wire_rows(graph, src) -> None:
    """Adds `new_positions` and `cross_source` (int32 [R]) after total_sequence_length and feeds
    them to every CachedAttention and CrossAttention. Raises ValueError when the graph has other
    self- or cross-attention (not the silk form) or already has the inputs."""
    from onnx import TensorProto, helper

    names = [i.name for i in graph.input]
    if NEW_POSITIONS in names or CROSS_SOURCE in names:
        raise ValueError(f"{src}: already a contract v4 graph ({NEW_POSITIONS} / {CROSS_SOURCE} inputs)")
    if "total_sequence_length" not in names:
        raise ValueError(f"{src}: no total_sequence_length input (not a contract decoder graph)")
    counts = {SILK_ATTENTION: 0, SILK_CROSS: 0}
    for node in graph.node:
        if node.domain == SILK_DOMAIN and node.op_type in counts:
            wanted = 7 if node.op_type == SILK_ATTENTION else 3
            if len(node.input) != wanted:
                raise ValueError(f"{src}: {node.op_type} '{node.name}' has {len(node.input)} inputs, expected {wanted}")
            node.input.append(NEW_POSITIONS if node.op_type == SILK_ATTENTION else CROSS_SOURCE)
            counts[node.op_type] += 1
        elif node.op_type in ("GroupQueryAttention", "Softmax"):
            raise ValueError(
                f"{src}: {node.op_type} '{node.name}' takes no per-row counts (contract v4 needs every "
                "attention in libsilk's CachedAttention / CrossAttention)"
            )
    if not counts[SILK_ATTENTION] or counts[SILK_ATTENTION] != counts[SILK_CROSS]:
        raise ValueError(
            f"{src}: {counts[SILK_ATTENTION]} CachedAttention and {counts[SILK_CROSS]} CrossAttention nodes"
        )
    for vi in graph.input:
        if vi.name.startswith("cross_"):
            _set_batch(vi, "S")
    at = names.index("total_sequence_length") + 1
    added = [helper.make_tensor_value_info(n, TensorProto.INT32, ["R"]) for n in (NEW_POSITIONS, CROSS_SOURCE)]
    inputs = list(graph.input)
    del graph.input[:]
    graph.input.extend(inputs[:at] + added + inputs[at:])
