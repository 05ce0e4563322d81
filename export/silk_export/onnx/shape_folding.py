# SPDX-License-Identifier: MIT
"""Shape arithmetic of an exported graph folded into constants. torch's exporter computes every
view()/reshape() target, F.normalize's expand and chunk()'s slice bounds at run time (Shape ->
Gather -> Unsqueeze -> Concat -> Reshape): 3,487 of the release-size INT4 decoder's 4,901 nodes,
tiny ones that onnxruntime runs on every call. Here each tensor's shape is
followed symbolically from the graph's inputs (a dim the inputs name, such as T, stays a symbol),
and each input a shape computation feeds becomes a constant where that is proven for every size the
inputs allow: a Reshape target keeps the input's dim with 0 and infers at most one with -1, slice
bounds become numbers, an Expand whose consumer broadcasts to the same shape anyway is dropped, and
the nodes nothing reads any more go. An op the pass does not know ends what it can follow there; the
graph computes exactly what it did (export/tests/test_shape_folding.py compares outputs bit for bit)."""

from __future__ import annotations

import itertools
import math

# A dim is an int or a symbol: ("in", name) for a dim the graph's inputs name, ("new", k) for one
# the pass cannot relate to others (equal only to itself), or (op, a, b) for arithmetic on dims.
_fresh = itertools.count()
_SMALL = 64  # int tensors with at most this many elements are followed as values
_UNARY = {
    "Cast",
    "Clip",
    "Erf",
    "Sqrt",
    "Neg",
    "Relu",
    "Sigmoid",
    "Tanh",
    "Softmax",
    "LogSoftmax",
    "Identity",
    "Abs",
    "Exp",
    "Log",
    "Reciprocal",
    "Not",
    "LayerNormalization",
    "Gelu",
    "Floor",
    "Ceil",
    "IsNaN",
}
_BROADCAST = {
    "Add",
    "Sub",
    "Mul",
    "Div",
    "Pow",
    "Max",
    "Min",
    "Equal",
    "Greater",
    "Less",
    "And",
    "Or",
    "Where",
    "GreaterOrEqual",
    "LessOrEqual",
    "Mod",
}
_ARITH = {
    "Add": lambda a, b: a + b,
    "Sub": lambda a, b: a - b,
    "Mul": lambda a, b: a * b,
    "Div": lambda a, b: (abs(a) // abs(b)) * (1 if (a < 0) == (b < 0) else -1) if b else None,
}  # truncating
_REDUCE = {"ReduceL2", "ReduceSum", "ReduceMean", "ReduceMax", "ReduceMin", "ReduceProd", "ReduceL1"}
_BIG = 1 << 62


def _new():
    return ("new", next(_fresh))


def _arith(op: str, a, b):
    """a op b on dims: computed when both are ints, simplified around 0 and 1, else a symbol."""
    if isinstance(a, int) and isinstance(b, int):
        r = _ARITH[op](a, b)
        return _new() if r is None else r
    if (op in ("Add", "Sub") and b == 0) or (op in ("Mul", "Div") and b == 1):
        return a
    if op in ("Add", "Mul") and a == (0 if op == "Add" else 1):
        return b
    if op == "Div" and isinstance(a, tuple) and a[0] == "Mul" and a[2] == b:
        return a[1]
    return (op, a, b)


def _broadcast(*shapes):
    """numpy broadcasting of symbolic shapes (an int > 1 wins over a symbol: the graph runs)."""
    if any(s is None for s in shapes):
        return None
    rank = max(len(s) for s in shapes)
    out = []
    for i in range(rank):
        dims = {s[i - rank + len(s)] for s in shapes if i - rank + len(s) >= 0} - {1}
        ints = [d for d in dims if isinstance(d, int)]
        out.append(ints[0] if ints else (dims.pop() if len(dims) == 1 else (1 if not dims else _new())))
    return out


def _axes(node, at: dict, values: dict, index: int = 1):
    """A node's axes: attribute `axes`, or its input `index` when that is a known value."""
    if "axes" in at:
        return list(at["axes"])
    if len(node.input) > index and node.input[index]:
        v = values.get(node.input[index])
        return list(v[0]) if v and all(isinstance(x, int) for x in v[0]) else None
    return []


def _reshaped(data, target):
    """Reshape's output dims for a symbolic target (0 = keep, -1 = the rest)."""
    out = [data[i] if d == 0 and i < len(data) else d for i, d in enumerate(target)]
    if -1 in out:
        num, den = list(data), [d for d in out if d != -1]
        for d in list(den):
            if d in num:
                num.remove(d)
                den.remove(d)
        rest = None
        if all(isinstance(d, int) for d in num + den):
            rest = math.prod(num) // math.prod(den) if math.prod(den) else None
        elif len(num) == 1 and not den:
            rest = num[0]
        out[out.index(-1)] = rest if rest is not None else _new()
    return out


def _slice_dim(dim, start: int, end: int, step: int):
    """A sliced dim: computed for an int, kept for a symbol sliced whole ([0, >= 2^62) step 1), else new."""
    if isinstance(dim, int):
        return len(range(*slice(start, end, step).indices(dim)))
    return dim if start == 0 and end >= _BIG and step == 1 else _new()


def _out_shapes(node, at: dict, shapes: dict, values: dict) -> list:
    """The symbolic shape of each output of `node` (None where the pass cannot tell)."""
    op, ins = node.op_type, [shapes.get(i) if i else None for i in node.input]
    known = lambda k: values.get(node.input[k])[0] if len(node.input) > k and node.input[k] in values else None  # noqa: E731
    if op in _UNARY:
        return [ins[0]] + [None] * (len(node.output) - 1)
    if op in _BROADCAST:
        return [_broadcast(*ins)]
    if op == "DynamicQuantizeLinear":  # the INT8 decoder's activations: y, scale [], zero point []
        return [ins[0], [], []]
    if op in ("MatMul", "MatMulInteger", "MatMulNBits", "Int4MatMul") and ins[0] and len(ins[0]) >= 2:
        if op in ("MatMulNBits", "Int4MatMul"):
            return [ins[0][:-1] + [at.get("N", _new())]]
        if ins[1] and len(ins[1]) >= 2:
            batch = _broadcast(ins[0][:-2], ins[1][:-2])
            return [batch + [ins[0][-2], ins[1][-1]]]
    if op == "GroupQueryAttention" and ins[0]:
        return [ins[0], None, None]
    if op == "Gather" and ins[0] and ins[1] is not None:
        axis = at.get("axis", 0) % len(ins[0])
        return [ins[0][:axis] + ins[1] + ins[0][axis + 1 :]]
    if op == "Transpose" and ins[0]:
        perm = at.get("perm", list(reversed(range(len(ins[0])))))
        return [[ins[0][p] for p in perm]]
    if op == "Reshape" and ins[0] is not None and known(1) is not None and not (_allows_zero(node) and 0 in known(1)):
        return [_reshaped(ins[0], known(1))]
    if op == "Expand" and ins[0] is not None and known(1) is not None:
        return [_broadcast(ins[0], known(1))]
    if op == "Shape" and ins[0] is not None:
        return [[len(ins[0][at.get("start", 0) : at.get("end", len(ins[0]))])]]
    if op == "Concat" and all(s is not None for s in ins) and ins:
        axis = at["axis"] % len(ins[0])
        total = ins[0][axis]
        for s in ins[1:]:
            total = _arith("Add", total, s[axis])
        return [ins[0][:axis] + [total] + ins[0][axis + 1 :]]
    if op in ("Unsqueeze", "Squeeze") and ins[0] is not None:
        axes = _axes(node, at, values)
        if axes is None:
            return [None]
        if op == "Squeeze":
            drop = {a % len(ins[0]) for a in axes} if axes else {i for i, d in enumerate(ins[0]) if d == 1}
            return [[d for i, d in enumerate(ins[0]) if i not in drop]]
        out, rank = list(ins[0]), len(ins[0]) + len(axes)
        for a in sorted(x % rank for x in axes):
            out.insert(a, 1)
        return [out]
    if op in _REDUCE and ins[0] is not None:
        axes = _axes(node, at, values)
        if axes is None:
            return [None]
        axes = {a % len(ins[0]) for a in axes} if axes else set(range(len(ins[0])))
        keep = at.get("keepdims", 1)
        return [[1 if i in axes else d for i, d in enumerate(ins[0]) if keep or i not in axes]]
    if op == "Slice" and ins[0] is not None:
        bounds = [known(k) for k in (1, 2)]
        axes = known(3) if len(node.input) > 3 and node.input[3] else list(range(len(bounds[0] or [])))
        steps = known(4) if len(node.input) > 4 and node.input[4] else [1] * len(axes or [])
        if all(b is not None and all(isinstance(x, int) for x in b) for b in (*bounds, axes, steps)):
            out = list(ins[0])
            for s, e, a, st in zip(*bounds, axes, steps):
                out[a % len(out)] = _slice_dim(out[a % len(out)], s, e, st)
            return [out]
    return [None] * len(node.output)


def _small_ints(t, base_dir):
    """(elements, dtype, scalar) of an int tensor of at most _SMALL elements and rank <= 1, else None.
    One stored in an external file is read from `base_dir` (None, or unreadable: not followed)."""
    from onnx import TensorProto, numpy_helper

    if t.data_type not in (TensorProto.INT64, TensorProto.INT32) or len(t.dims) > 1 or math.prod(t.dims) > _SMALL:
        return None
    if t.data_location == TensorProto.EXTERNAL and base_dir is None:
        return None
    try:
        arr = numpy_helper.to_array(t, str(base_dir or ""))
    except Exception:  # unreadable external data: not followed (onnxruntime names the problem on load)
        return None
    return [int(x) for x in arr.reshape(-1)], t.data_type, len(t.dims) == 0


def _out_value(node, at: dict, values: dict, shapes: dict, base_dir=None):
    """(elements, dtype, scalar) of a small int output computed from shapes and constants, else None."""
    from onnx import TensorProto

    op = node.op_type
    v = [values.get(i) for i in node.input if i]
    if op == "Constant":
        return _small_ints(at["value"], base_dir) if "value" in at else None
    if op == "Shape" and shapes.get(node.input[0]) is not None:
        s = shapes[node.input[0]]
        return s[at.get("start", 0) : at.get("end", len(s))], TensorProto.INT64, False
    if not v or any(x is None for x in v):
        return None
    if op in ("Identity", "Cast"):
        dtype = at.get("to", v[0][1])
        return (v[0][0], dtype, v[0][2]) if dtype in (TensorProto.INT64, TensorProto.INT32) else None
    if op == "Gather" and len(v) == 2 and all(isinstance(i, int) for i in v[1][0]):
        n = len(v[0][0])
        picked = [v[0][0][i % n] for i in v[1][0]] if all(-n <= i < n for i in v[1][0]) else None
        return None if picked is None else (picked, v[0][1], v[1][2])
    if op == "Unsqueeze" and v[0][2]:
        return v[0][0], v[0][1], False
    if op == "Squeeze" and len(v[0][0]) == 1:
        return v[0][0], v[0][1], True
    if op == "Concat":
        return [d for x in v for d in x[0]], v[0][1], False
    if op in _ARITH and len(v) == 2:
        a, b = v[0][0], v[1][0]
        if len(a) != len(b) and 1 not in (len(a), len(b)):
            return None
        n = max(len(a), len(b))
        a, b = a * n if len(a) == 1 else a, b * n if len(b) == 1 else b
        return [_arith(op, x, y) for x, y in zip(a, b)], v[0][1], v[0][2] and v[1][2]
    return None


def _dims(vi):
    """A graph input's or initializer's dims: ints, ("in", name) for a named dim, new symbols else."""
    if hasattr(vi, "dims"):
        return [int(d) for d in vi.dims]
    t = vi.type.tensor_type
    if not t.HasField("shape"):
        return None
    return [
        d.dim_value if d.HasField("dim_value") else (("in", d.dim_param) if d.dim_param else _new())
        for d in t.shape.dim
    ]


def follow(graph, base_dir=None) -> tuple[dict, dict]:
    """(symbolic shape of every tensor it can follow, (elements, dtype, scalar) of every small int
    tensor computed from shapes and constants), in one pass over the (topologically sorted) nodes.
    `base_dir`: where the graph's external data lies (small int constants stored there are read)."""
    from onnx import helper

    shapes = {vi.name: _dims(vi) for vi in graph.input}
    values = {}
    for t in graph.initializer:
        if t.name in shapes:  # also a graph input: a feed may replace it, so it is no constant
            continue
        shapes[t.name] = _dims(t)
        value = _small_ints(t, base_dir)
        if value is not None:
            values[t.name] = value
    for node in graph.node:
        at = {a.name: helper.get_attribute_value(a) for a in node.attribute}
        try:
            value = _out_value(node, at, values, shapes, base_dir)
            out = _out_shapes(node, at, shapes, values)
            if node.op_type == "Constant" and "value" in at:
                out = [[int(d) for d in at["value"].dims]]
        except (IndexError, KeyError, TypeError, ValueError, ZeroDivisionError):
            value, out = None, []  # a node that does not fit its inputs: not followed (onnxruntime says why)
        if value is not None:
            values[node.output[0]] = value
        for name, shape in zip(node.output, out):
            shapes[name] = shape
    return shapes, values


def _reshape_target(data, target):
    """A Reshape target with symbols as a constant (0 = the input's dim there, one -1), else None."""
    if data is None:
        return None
    out = [d if isinstance(d, int) else (0 if i < len(data) and data[i] == d else None) for i, d in enumerate(target)]
    if out.count(None) > 1 or (None in out and -1 in out):
        return None
    return [-1 if d is None else d for d in out]


def _allows_zero(node) -> bool:
    """Reshape with allowzero=1: a 0 in its target is a zero dim, not "keep the input's"."""
    return any(a.name == "allowzero" and a.i for a in node.attribute)


def _constant_inputs(graph, shapes: dict, values: dict) -> int:
    """Each input of a data node (one whose output is not a followed value) that shape arithmetic
    computes becomes an initializer. Returns how many."""
    from onnx import helper

    computed = {o for n in graph.node if n.op_type != "Constant" for o in n.output}
    made = 0
    for node in graph.node:
        if node.op_type == "Constant" or all(o in values for o in node.output):
            continue
        for k, name in enumerate(node.input):
            if name not in computed or name not in values:
                continue
            elems, dtype, scalar = values[name]
            if node.op_type == "Reshape" and k == 1 and not _allows_zero(node):
                elems = _reshape_target(shapes.get(node.input[0]), elems)
            if elems is None or not all(isinstance(d, int) for d in elems):
                continue
            const = f"{name}_folded_{made}"
            graph.initializer.append(helper.make_tensor(const, dtype, [] if scalar else [len(elems)], elems))
            node.input[k] = const
            made += 1
    return made


def _drop_expands(graph, shapes: dict) -> int:
    """Expand(x, s) read only by Add/Sub/Mul/Div whose other operand already has the expanded shape
    is x itself to them (they broadcast): their input becomes x. Returns how many were bypassed."""
    outputs = {o.name for o in graph.output}
    readers = {}
    for n in graph.node:
        for i in n.input:
            readers.setdefault(i, []).append(n)
    bypassed = 0
    for node in graph.node:
        e = node.output[0] if node.op_type == "Expand" else None
        if (
            e is None
            or e in outputs
            or shapes.get(e) is None
            or any(isinstance(d, tuple) and d[0] == "new" for d in shapes[e])
        ):
            continue
        users = readers.get(e, [])
        if not users or any(
            u.op_type not in ("Add", "Sub", "Mul", "Div")
            or list(u.input).count(e) != 1
            or shapes.get(u.input[1 - list(u.input).index(e)]) != shapes[e]
            for u in users
        ):
            continue
        for u in users:
            u.input[list(u.input).index(e)] = node.input[0]
        bypassed += 1
    return bypassed


def _prune(graph) -> int:
    """Removes the nodes whose outputs nothing reads (and the values they described). Returns how many."""
    live = {o.name for o in graph.output}
    kept = []
    for node in reversed(graph.node):
        if any(o in live for o in node.output):
            kept.append(node)
            live.update(i for i in node.input if i)
    removed = len(graph.node) - len(kept)
    del graph.node[:]
    graph.node.extend(reversed(kept))
    produced = {o for n in graph.node for o in n.output} | {i.name for i in graph.input}
    vis = [vi for vi in graph.value_info if vi.name in produced]
    del graph.value_info[:]
    graph.value_info.extend(vis)
    read = {i for n in graph.node for i in n.input}
    inits = [t for t in graph.initializer if t.name in read or "_folded_" not in t.name]
    del graph.initializer[:]
    graph.initializer.extend(inits)
    return removed


def fold_shapes(graph, base_dir=None) -> dict:
    """Folds `graph`'s shape arithmetic in place (see above; `base_dir`: where its external data
    lies). Returns counts: constants made, expands bypassed, nodes removed."""
    shapes, values = follow(graph, base_dir)
    made = _constant_inputs(graph, shapes, values)
    bypassed = _drop_expands(graph, shapes)
    return {"constants": made, "expands": bypassed, "removed": _prune(graph)}
