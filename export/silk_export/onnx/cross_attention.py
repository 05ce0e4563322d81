# SPDX-License-Identifier: MIT
"""The ai.silk CrossAttention form of a decoder's attention over the point cloud
(docs/model_contract.md). The exported graph computes each layer's cross-attention as
MatMul(q, Transpose(cross_key_l)) -> Mul(scale) -> Softmax -> MatMul(., cross_value_l);
onnxruntime 1.22 runs the first product as a batch of tiny matrix products that read the 51 MB of
the release network's cross keys and values at about a third of memory speed on every call.
libsilk's CrossAttention computes the same in one node, reading each row once. The fp16 and int8
cache variants ("silk" form) use it, with the cross_* inputs float16 when CrossAttention is all
that reads them (half_cross_inputs: the cross K/V is a seventh of a call's reads at depth 2,000;
the runtime converts the encoder's output once per mesh); the fp32-cache decoder files keep the
plain operators and float32 inputs."""

from __future__ import annotations

import collections

from .silk_ops import SILK_CROSS, SILK_DOMAIN


def _scalar(graph, name: str, producers: dict):
    """The float value of a one-element constant (Constant node or initializer), else None."""
    from onnx import numpy_helper

    node = producers.get(name)
    tensor = None
    if node is not None and node.op_type == "Constant" and node.attribute and node.attribute[0].name == "value":
        tensor = node.attribute[0].t
    if node is None:
        tensor = next((t for t in graph.initializer if t.name == name), None)
    if tensor is None:
        return None
    value = numpy_helper.to_array(tensor)
    return float(value.reshape(-1)[0]) if value.size == 1 else None


def _match(graph, m2, producers: dict, users: collections.Counter, inputs: set):
    """(nodes to remove, query name, key name, scale) when MatMul `m2` ends the cross-attention
    pattern above, else None."""
    from onnx import helper

    if m2.op_type != "MatMul" or m2.input[1] not in inputs or not m2.input[1].startswith("cross_value"):
        return None
    sm = producers.get(m2.input[0])
    if sm is None or sm.op_type != "Softmax" or users[sm.output[0]] != 1:
        return None
    if {a.name: helper.get_attribute_value(a) for a in sm.attribute}.get("axis", -1) not in (-1, 3):
        return None
    mul = producers.get(sm.input[0])
    if mul is None or mul.op_type != "Mul" or users[mul.output[0]] != 1:
        return None
    for i in (0, 1):
        m1, scale = producers.get(mul.input[i]), _scalar(graph, mul.input[1 - i], producers)
        if m1 is not None and m1.op_type == "MatMul" and scale is not None and users[m1.output[0]] == 1:
            break
    else:
        return None
    tr = producers.get(m1.input[1])
    if tr is None or tr.op_type != "Transpose" or tr.input[0] not in inputs or not tr.input[0].startswith("cross_key"):
        return None
    if [helper.get_attribute_value(a) for a in tr.attribute if a.name == "perm"] != [[0, 1, 3, 2]]:
        return None
    removed = [m1, mul, sm, m2] + ([tr] if users[tr.output[0]] == 1 else [])
    return removed, m1.input[0], tr.input[0], scale


def to_cross_attention(graph) -> int:
    """Rewrites, in place, each cross-attention of `graph` in the pattern above into one ai.silk
    CrossAttention node (query, cross_key_l, cross_value_l; attribute scale). Returns how many."""
    from onnx import helper

    producers = {o: n for n in graph.node for o in n.output}
    users = collections.Counter(i for n in graph.node for i in n.input)
    users.update(o.name for o in graph.output)
    inputs = {i.name for i in graph.input}
    replace, drop = {}, set()
    for node in graph.node:
        found = _match(graph, node, producers, users, inputs)
        if found:
            removed, query, key, scale = found
            replace[id(node)] = helper.make_node(
                SILK_CROSS,
                [query, key, node.input[1]],
                [node.output[0]],
                name=f"{node.name}_cross",
                domain=SILK_DOMAIN,
                scale=scale,
            )
            drop |= {id(n) for n in removed if n is not node}
    nodes = [replace.get(id(n), n) for n in graph.node if id(n) not in drop]
    del graph.node[:]
    graph.node.extend(nodes)
    return len(replace)


def half_cross_inputs(graph) -> int:
    """Makes each graph input cross_key_l / cross_value_l float16 when every node that reads it is
    ai.silk CrossAttention (which reads float16 rows as well as float32); an input anything else
    reads stays float32. Returns how many became float16."""
    from onnx import TensorProto

    readers = collections.defaultdict(list)
    for n in graph.node:
        for i in n.input:
            readers[i].append(n)
    count = 0
    for vi in graph.input:
        users = readers.get(vi.name, [])
        if (
            vi.name.startswith("cross_")
            and users
            and all(u.op_type == SILK_CROSS and u.domain == SILK_DOMAIN for u in users)
        ):
            vi.type.tensor_type.elem_type = TensorProto.FLOAT16
            count += 1
    return count
