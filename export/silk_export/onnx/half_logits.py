# SPDX-License-Identifier: MIT
"""The float16 logits head of a decoder's fp16/int8-cache variants (docs/model_contract.md, "Logits
head"). The export keeps the head (d_model x vocabulary: 42 MB for the release network) float32 even
in the INT4 decoder, because the logits decide every sampled id; at depth it is still a tenth of
what each call reads. The "silk" form stores it as float16 [vocabulary, d_model] and computes it
with libsilk's ai.silk HalfMatMul (float32 products and sums): half the bytes, a rounding of each
weight to 11 significant bits, measured with the cache precisions (benchmarks.md, "KV precision")."""

from __future__ import annotations

from pathlib import Path

from .silk_ops import SILK_DOMAIN, SILK_HALF

LOGITS = "logits"


def _logits_matmul(graph):
    """(MatMul, weight initializer, Cast or None) for the MatMul whose product is the graph output
    `logits`, directly or through one Add (the bias), when its weight is a float32 [K, N]
    initializer or a Cast to float32 of a float16 one (how a model stored in float16 keeps it);
    else None."""
    from onnx import TensorProto

    producers = {o: n for n in graph.node for o in n.output}
    node = producers.get(LOGITS)
    if node is not None and node.op_type == "Add":
        node = next((producers[i] for i in node.input if i in producers and producers[i].op_type == "MatMul"), None)
    if node is None or node.op_type != "MatMul" or node.domain not in ("", "ai.onnx"):
        return None
    inits = {t.name: t for t in graph.initializer}
    cast, name = producers.get(node.input[1]), node.input[1]
    want = TensorProto.FLOAT
    if cast is not None:
        to = next((a.i for a in cast.attribute if a.name == "to"), None)
        if cast.op_type != "Cast" or to != TensorProto.FLOAT:
            return None
        name, want = cast.input[0], TensorProto.FLOAT16
    weight = inits.get(name)
    if weight is None or weight.data_type != want or len(weight.dims) != 2:
        return None
    return node, weight, cast


def _weight(t, base_dir: Path):
    """The float32 or float16 array of initializer `t`; one stored as external data is read from
    its file under `base_dir` (directly: onnx's reader refuses files with several hard links, which
    model folders made with `cp -l` have). Raises ValueError naming the file when that fails."""
    import numpy as np
    from onnx import TensorProto, numpy_helper

    if t.data_location != TensorProto.EXTERNAL:
        return numpy_helper.to_array(t)
    info = {e.key: e.value for e in t.external_data}
    location = Path(info.get("location", ""))
    count, size = int(np.prod(t.dims)), 2 if t.data_type == TensorProto.FLOAT16 else 4
    if not info.get("location") or location.is_absolute() or ".." in location.parts:
        raise ValueError(
            f"{t.name}: external data location '{info.get('location', '')}' is not a file beside the graph"
        )
    path, offset = Path(base_dir) / location, int(info.get("offset", 0))
    try:
        with open(path, "rb") as f:
            f.seek(offset)
            data = f.read(size * count)
    except OSError as e:
        raise ValueError(f"{path}: cannot read {t.name} ({e.strerror})") from None
    if len(data) != size * count:
        raise ValueError(f"{path}: {t.name} needs {size * count} bytes at offset {offset}, the file has {len(data)}")
    return np.frombuffer(data, "<f2" if size == 2 else "<f4").reshape(tuple(t.dims))


def to_half_logits(graph, base_dir: Path) -> bool:
    """Rewrites, in place, the logits head of `graph` into ai.silk HalfMatMul with a float16
    [N, K] copy of its [K, N] weight (read from `base_dir` when stored as external data; a float16
    weight behind a Cast is copied exactly); the original weight (and Cast) is dropped when
    nothing else reads it. Returns whether a head was rewritten (False: no MatMul with such a
    constant weight makes `logits`, and nothing changed)."""
    import numpy as np
    from onnx import numpy_helper

    found = _logits_matmul(graph)
    if found is None:
        return False
    node, weight, cast = found
    w = _weight(weight, base_dir)
    half = numpy_helper.from_array(np.ascontiguousarray(w.T).astype(np.float16), f"{weight.name}__half")
    graph.initializer.append(half)
    node.op_type, node.domain = SILK_HALF, SILK_DOMAIN
    replaced = node.input[1]
    node.input[1] = half.name
    outputs = {o.name for o in graph.output}
    if cast is not None and not any(replaced in n.input for n in graph.node) and replaced not in outputs:
        graph.node.remove(cast)
    if not any(weight.name in n.input for n in graph.node) and weight.name not in outputs:
        graph.initializer.remove(weight)
    return True
