# SPDX-License-Identifier: MIT
"""libsilk's ai.silk CachedAttention op (the attention of fp16- and int8-cache decoders), run by
Python's onnxruntime with libsilk registered as its custom-op library: against a numpy reference,
in place (present bound to past's buffer, as libsilk runs it) and copying, against
GroupQueryAttention with float16 casts, and its errors for inputs that do not fit together."""

from __future__ import annotations

import numpy as np
import pytest

onnx = pytest.importorskip("onnx")
ort = pytest.importorskip("onnxruntime")

from onnx import TensorProto, helper  # noqa: E402

from silk_export.onnx.decode import session  # noqa: E402

H, KVH, D = 4, 2, 16


def _graph(path, op="CachedAttention", domain="ai.silk", cache=TensorProto.FLOAT16, new_positions=False, **attrs):
    # Symbolic dims, so onnxruntime passes shapes that do not fit through to the op's own checks;
    # new_positions: contract v4's optional eighth input.
    row = D + 4 if cache == TensorProto.INT8 else D
    io = [
        ("q", TensorProto.FLOAT, ["B", "T", "QD"]),
        ("k", TensorProto.FLOAT, ["B", "T", "KD"]),
        ("v", TensorProto.FLOAT, ["B", "T", "KD"]),
        ("past_key", cache, ["B", "KV", "C", "D"]),
        ("past_value", cache, ["B", "KV", "C", "D"]),
        ("seqlens_k", TensorProto.INT32, ["R"]),
        ("total_sequence_length", TensorProto.INT32, []),
    ] + ([("new_positions", TensorProto.INT32, ["R"])] if new_positions else [])
    outs = [
        ("out", TensorProto.FLOAT, ["B", "T", H * D]),
        ("present_key", cache, ["B", KVH, "P", row]),
        ("present_value", cache, ["B", KVH, "P", row]),
    ]
    node = helper.make_node(
        op,
        [n for n, _, _ in io],
        [n for n, _, _ in outs],
        name="attn",
        domain=domain,
        num_heads=H,
        kv_num_heads=KVH,
        **attrs,
    )
    g = helper.make_graph(
        [node], "g", [helper.make_tensor_value_info(*x) for x in io], [helper.make_tensor_value_info(*x) for x in outs]
    )
    m = helper.make_model(g, opset_imports=[helper.make_opsetid("", 17), helper.make_opsetid(domain, 1)], ir_version=8)
    onnx.save(m, str(path))
    return path


def _inputs(T, P, C, seed=0):
    r = np.random.default_rng(seed)
    past = [np.zeros((1, KVH, C, D), np.float16) for _ in range(2)]
    for p in past:
        p[:, :, :P] = r.normal(size=(1, KVH, P, D)).astype(np.float16)
    return {
        "q": r.normal(size=(1, T, H * D)).astype(np.float32) * 0.5,
        "k": r.normal(size=(1, T, KVH * D)).astype(np.float32),
        "v": r.normal(size=(1, T, KVH * D)).astype(np.float32),
        "past_key": past[0],
        "past_value": past[1],
        "seqlens_k": np.array([P + T - 1], np.int32),
        "total_sequence_length": np.array(P + T, np.int32),
    }


def _int16_query(q):
    """The query as int8 caches score it (docs/model_contract.md): q16 = round half to even
    (q * 32767 / max|q|) in float32, times max|q| / 32767; a zero query stays zero."""
    top = np.float32(np.abs(q).max())
    if top == 0:
        return np.zeros(q.shape)
    return np.rint(q * (np.float32(32767) / top)).astype(np.float64) * float(top / np.float32(32767))


def _attend(x, keys, vals, scale, query=lambda q: q.astype(np.float64)):
    """softmax(scale q.k) v in float64 over the cache rows [kv head, position, D], causally;
    `query` gives the query as the kernel scores it."""
    T, P = x["q"].shape[1], int(x["total_sequence_length"]) - x["q"].shape[1]
    out = np.zeros((T, H, D))
    for t in range(T):
        for h in range(H):
            s = scale * keys[h // (H // KVH), : P + t + 1] @ query(x["q"][0, t, h * D : (h + 1) * D])
            w = np.exp(s - s.max())
            out[t, h] = w @ vals[h // (H // KVH), : P + t + 1] / w.sum()
    return out.reshape(1, T, H * D)


def _reference(x, scale):
    T, P = x["q"].shape[1], int(x["total_sequence_length"]) - x["q"].shape[1]
    keys = np.concatenate(
        [x["past_key"][0, :, :P], x["k"][0].reshape(T, KVH, D).transpose(1, 0, 2).astype(np.float16)], 1
    )
    vals = np.concatenate(
        [x["past_value"][0, :, :P], x["v"][0].reshape(T, KVH, D).transpose(1, 0, 2).astype(np.float16)], 1
    )
    keys, vals = keys.astype(np.float64), vals.astype(np.float64)
    return _attend(x, keys, vals, scale), keys, vals


@pytest.mark.parametrize("T,P", [(1, 0), (1, 9), (4, 0), (3, 20)])
def test_copying_matches_reference(tmp_path, T, P):
    s = session(_graph(tmp_path / "a.onnx", scale=0.7))
    x = _inputs(T, P, P)
    out, pk, pv = s.run(None, x)
    ref, keys, vals = _reference(x, 0.7)
    np.testing.assert_allclose(out, ref, atol=2e-5)
    assert pk.shape == (1, KVH, P + T, D) and pk.dtype == np.float16
    np.testing.assert_array_equal(pk[0].astype(np.float64), keys)
    np.testing.assert_array_equal(pv[0].astype(np.float64), vals)


def _run_in_place(s, x):
    """Runs `x` with present_* bound to past_*'s own buffers (libsilk's cache); returns the attention
    output and the key and value buffers after the call."""
    b = s.io_binding()
    vals = {n: ort.OrtValue.ortvalue_from_numpy(a) for n, a in x.items()}
    for n, v in vals.items():
        b.bind_ortvalue_input(n, v)
    b.bind_output("out")
    b.bind_ortvalue_output("present_key", vals["past_key"])
    b.bind_ortvalue_output("present_value", vals["past_value"])
    s.run_with_iobinding(b)
    return b.copy_outputs_to_cpu()[0], vals["past_key"].numpy(), vals["past_value"].numpy()


def _in_place_and_copying(s, x, past: int):
    """Runs `x` once copying (past_* cut to `past` rows) and once in place (present_* bound to
    past_*'s own buffers, libsilk's cache); asserts equal outputs and that the in-place buffer
    holds the copying run's present rows. Returns (copying outputs, the in-place key buffer)."""
    copy = s.run(
        None, {**x, "past_key": x["past_key"][:, :, :past].copy(), "past_value": x["past_value"][:, :, :past].copy()}
    )
    out, in_place, _ = _run_in_place(s, x)
    np.testing.assert_array_equal(out, copy[0])
    np.testing.assert_array_equal(in_place[:, :, : copy[1].shape[2]], copy[1])
    return copy, in_place


def test_in_place_writes_the_past_buffer_and_matches_copying(tmp_path):
    """present_* bound to past_*'s own memory (libsilk's in-place cache): the new rows land there."""
    s = session(_graph(tmp_path / "a.onnx"))  # no scale: 1 / sqrt(head_dim), as GroupQueryAttention
    x = _inputs(2, 7, 12)
    copy, _ = _in_place_and_copying(s, x, 7)
    np.testing.assert_allclose(copy[0], _reference(x, 1 / np.sqrt(D))[0], atol=2e-5)


def test_close_to_group_query_attention_with_float16_casts(tmp_path):
    """The "ort" form of the fp16 variant computes the same attention (q, k, v and the output
    rounded to float16 there, so agreement is to float16 precision)."""
    s = session(_graph(tmp_path / "a.onnx", scale=0.5))
    gqa_path = tmp_path / "gqa.onnx"
    _graph(gqa_path, op="GroupQueryAttention", domain="com.microsoft", cache=TensorProto.FLOAT16, scale=0.5)
    m = onnx.load(str(gqa_path))  # float16 q, k, v and output for GroupQueryAttention
    for vi in list(m.graph.input)[:3] + [m.graph.output[0]]:
        vi.type.tensor_type.elem_type = TensorProto.FLOAT16
    onnx.save(m, str(gqa_path))
    x = _inputs(3, 30, 30, seed=4)
    half = {**x, **{n: x[n].astype(np.float16) for n in ("q", "k", "v")}}
    ours, theirs = s.run(None, x), session(gqa_path).run(None, half)
    np.testing.assert_allclose(ours[0], theirs[0].astype(np.float32), atol=3e-3)
    np.testing.assert_array_equal(ours[1], theirs[1])


def _expect_refused(s, x, change, message):
    """`change` applied to the inputs `x` makes session `s` fail with `message`, naming the node."""
    change(x)
    with pytest.raises(Exception, match=message) as e:
        s.run(None, x)
    assert "CachedAttention 'attn'" in str(e.value)


@pytest.mark.parametrize(
    "change,message",
    [
        (lambda x: x.update(seqlens_k=np.array([40], np.int32)), "do not fit together"),
        (
            lambda x: x.update(total_sequence_length=np.array(99, np.int32), seqlens_k=np.array([98], np.int32)),
            "do not fit together",
        ),
        (lambda x: x.update(past_key=np.zeros((1, KVH + 1, 8, D), np.float16)), "past_key/past_value have shapes"),
        (lambda x: x.update(q=np.zeros((2, 1, H * D), np.float32)), r"key/value have shapes .*expected \[2, 1, 32\]"),
        (lambda x: x.update(k=np.zeros((1, 2, KVH * D), np.float32)), "key/value have shapes"),
    ],
)
def test_inputs_that_do_not_fit_are_refused_naming_the_node(tmp_path, change, message):
    _expect_refused(session(_graph(tmp_path / "a.onnx")), _inputs(1, 8, 8), change, message)


def _batch(pasts, news, T, C, seed=0):
    """Contract v4 inputs: one row per entry of `pasts` (its cache depth) and `news` (its count of new
    positions, padded to T), each row's cache block of C rows."""
    rows = [_inputs(T, p, C, seed=seed + i) for i, p in enumerate(pasts)]
    x = {n: np.concatenate([r[n] for r in rows]) for n in ("q", "k", "v", "past_key", "past_value")}
    x["seqlens_k"] = np.array([p + n - 1 for p, n in zip(pasts, news)], np.int32)
    x["total_sequence_length"] = np.array(max(p + n for p, n in zip(pasts, news)), np.int32)
    x["new_positions"] = np.array(news, np.int32)
    return x


def _alone(s, x, r, past, new):
    """Row r of batch inputs `x` run alone through the contract-v3 graph (no new_positions), copying."""
    one = {n: x[n][r : r + 1, :new].copy() for n in ("q", "k", "v")}
    one.update({n: x[n][r : r + 1, :, :past].copy() for n in ("past_key", "past_value")})
    one.update(seqlens_k=np.array([past + new - 1], np.int32), total_sequence_length=np.array(past + new, np.int32))
    return s.run(None, one)


@pytest.mark.parametrize("cache", [TensorProto.FLOAT16, TensorProto.INT8])
def test_batch_rows_are_bit_identical_to_each_row_alone(tmp_path, cache):
    """Contract v4: rows at depths 0, 5 and 9 taking 1, 3 (a forced run: the whole chunk) and 2 new
    positions in one call, copying and in place: each row's output and cache rows are those of the row
    run alone; padding positions give zeros."""
    batched = session(_graph(tmp_path / "b.onnx", cache=cache, new_positions=True, scale=0.7))
    single = session(_graph(tmp_path / "a.onnx", cache=cache, scale=0.7))
    pasts, news = [0, 5, 9], [1, 3, 2]
    x = _batch(pasts, news, 3, 12)
    if cache == TensorProto.INT8:  # int8 rows of the contract's layout: D values, then a float32 scale
        for n in ("past_key", "past_value"):
            x[n] = np.concatenate([x[n].astype(np.int8), np.zeros(x[n].shape[:3] + (4,), np.int8)], -1)
            x[n][..., D:] = np.frombuffer(np.float32(0.01).tobytes(), np.int8)
    cut = {n: x[n][:, :, : max(pasts)].copy() for n in ("past_key", "past_value")}
    copy = batched.run(None, {**x, **cut})  # each row's past copied into a new present of 11 rows
    out_in_place, key_in_place, value_in_place = _run_in_place(batched, x)
    np.testing.assert_array_equal(out_in_place, copy[0])
    for r, (p, n) in enumerate(zip(pasts, news)):
        out, pk, pv = _alone(single, x, r, p, n)
        np.testing.assert_array_equal(copy[0][r, :n], out[0], err_msg=f"row {r}")
        assert not copy[0][r, n:].any(), f"row {r}: padding positions must be zeros"
        np.testing.assert_array_equal(copy[1][r, :, : p + n], pk[0], err_msg=f"row {r} keys")
        np.testing.assert_array_equal(copy[2][r, :, : p + n], pv[0], err_msg=f"row {r} values")
        np.testing.assert_array_equal(key_in_place[r, :, : p + n], pk[0], err_msg=f"row {r} keys in place")
        np.testing.assert_array_equal(value_in_place[r, :, : p + n], pv[0], err_msg=f"row {r} values in place")


@pytest.mark.parametrize(
    "change,message",
    [
        (lambda x: x.update(new_positions=np.array([1, 4, 2], np.int32)), "row 1: seqlens_k 7, 4 new positions"),
        (lambda x: x.update(new_positions=np.array([1, 3], np.int32)), r"new_positions has shape \[2\]"),
        (lambda x: x.update(seqlens_k=np.array([0, 7], np.int32)), r"seqlens_k must have shape \[3\]"),
        (lambda x: x.update(total_sequence_length=np.array(12, np.int32)), "total_sequence_length 12"),
        (lambda x: x.update(past_key=x["past_key"][:2]), r"expected \[R, kv_heads, capacity, head_dim\]"),
    ],
)
def test_batch_inputs_that_do_not_fit_are_refused_naming_the_node(tmp_path, change, message):
    _expect_refused(
        session(_graph(tmp_path / "b.onnx", new_positions=True)), _batch([0, 5, 9], [1, 3, 2], 3, 12), change, message
    )


def test_attributes_it_does_not_implement_are_refused(tmp_path):
    from silk_export.onnx.kv_precision import make_kv16_decoder

    path = _graph(
        tmp_path / "decoder.onnx",
        op="GroupQueryAttention",
        domain="com.microsoft",
        cache=TensorProto.FLOAT,
        do_rotary=1,
    )
    m = onnx.load(str(path))
    for vi in m.graph.input[3:5]:
        vi.name = vi.name.replace("past_key", "past_key_0").replace("past_value", "past_value_0")
    m.graph.node[0].input[3], m.graph.node[0].input[4] = "past_key_0", "past_value_0"
    onnx.save(m, str(path))
    with pytest.raises(ValueError, match="do_rotary=1, which CachedAttention does not implement"):
        make_kv16_decoder(path, tmp_path / "x.onnx")
    make_kv16_decoder(path, tmp_path / "x.onnx", attention="ort")  # the cast form keeps any attribute


# --- int8 caches: rows of D int8 values + the row's float32 scale (docs/model_contract.md) ---


def _quantize(x):
    """Rows [..., D] float32 -> [..., D + 4] int8 by the contract: scale = max|x| / 127,
    q = round half to even (x / scale) (all zeros for a zero row), then the scale's 4 bytes."""
    x = np.asarray(x, np.float32)
    scale = (np.abs(x).max(-1, keepdims=True) / np.float32(127)).astype(np.float32)
    safe = np.where(scale > 0, scale, np.float32(1))
    q = np.where(scale > 0, np.clip(np.rint(x / safe), -127, 127), 0).astype(np.int8)
    return np.concatenate([q, scale.astype("<f4").view(np.int8)], -1)


def _dequantize(rows):
    scale = np.ascontiguousarray(rows[..., D:]).view("<f4").astype(np.float64)
    return rows[..., :D].astype(np.float64) * scale


def _inputs8(T, P, C, seed=0):
    r = np.random.default_rng(seed)
    x = _inputs(T, P, C, seed)
    for name in ("past_key", "past_value"):
        past = np.zeros((1, KVH, C, D + 4), np.int8)
        past[:, :, :P] = _quantize(r.normal(size=(1, KVH, P, D)))
        x[name] = past
    return x


def _reference8(x, scale):
    T, P = x["q"].shape[1], int(x["total_sequence_length"]) - x["q"].shape[1]
    new = {n: _quantize(x[n][0].reshape(T, KVH, D).transpose(1, 0, 2)) for n in ("k", "v")}
    rows = {n: np.concatenate([x[f"past_{w}"][0, :, :P], new[n]], 1) for n, w in (("k", "key"), ("v", "value"))}
    keys, vals = _dequantize(rows["k"]), _dequantize(rows["v"])
    return _attend(x, keys, vals, scale, _int16_query), rows["k"], rows["v"]


@pytest.mark.parametrize("T,P", [(1, 0), (1, 9), (4, 0), (3, 20)])
def test_int8_copying_matches_reference(tmp_path, T, P):
    s = session(_graph(tmp_path / "a.onnx", cache=TensorProto.INT8, scale=0.7))
    x = _inputs8(T, P, P)
    out, pk, pv = s.run(None, x)
    ref, keys, vals = _reference8(x, 0.7)
    np.testing.assert_allclose(out, ref, atol=2e-6)  # the float query would be 5e-5 away
    assert pk.shape == (1, KVH, P + T, D + 4) and pk.dtype == np.int8
    np.testing.assert_array_equal(pk[0], keys)  # the new rows quantized exactly as the contract says
    np.testing.assert_array_equal(pv[0], vals)


def test_int8_in_place_writes_the_past_buffer_and_matches_copying(tmp_path):
    s = session(_graph(tmp_path / "a.onnx", cache=TensorProto.INT8))
    x = _inputs8(2, 7, 12)
    x["k"][0, 1, :D] = 0  # a zero row: scale 0
    copy, in_place = _in_place_and_copying(s, x, 7)
    assert not in_place[0, 0, 8].any()  # the zero row: int8 zeros and a scale of +0.0
    assert (in_place[:, :, 9:] == 0).all()  # rows past P + T untouched
    np.testing.assert_allclose(copy[0], _reference8(x, 1 / np.sqrt(D))[0], atol=2e-6)


@pytest.mark.parametrize(
    "change,message",
    [
        (
            lambda x: x.update(
                past_key=np.zeros((1, KVH, 8, D), np.int8), past_value=np.zeros((1, KVH, 8, D), np.int8)
            ),
            rf"expected \[R, kv_heads, capacity, head_dim \+ 4\] = \[1, {KVH}, C, {D + 4}\]",
        ),
        (lambda x: x.update(past_key=np.zeros((1, KVH, 8, D + 4), np.int8)), "past_key/past_value have shapes"),
        (lambda x: x.update(seqlens_k=np.array([40], np.int32)), "do not fit together"),
    ],
)
def test_int8_inputs_that_do_not_fit_are_refused_naming_the_node(tmp_path, change, message):
    _expect_refused(session(_graph(tmp_path / "a.onnx", cache=TensorProto.INT8)), _inputs8(1, 8, 9), change, message)


def test_one_op_name_serves_both_cache_types(tmp_path):
    """float16 and int8 caches are two kernels of the one ai.silk CachedAttention; a float32 cache
    is neither and onnxruntime refuses the graph."""
    assert session(_graph(tmp_path / "h.onnx")).get_inputs()[3].type == "tensor(float16)"
    assert session(_graph(tmp_path / "i.onnx", cache=TensorProto.INT8)).get_inputs()[3].type == "tensor(int8)"
    with pytest.raises(Exception, match="past_key"):
        session(_graph(tmp_path / "f.onnx", cache=TensorProto.FLOAT))
