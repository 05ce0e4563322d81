# SPDX-License-Identifier: MIT
"""`silk-export import-official` on a checkpoint built at test time from the release's key list
(official-model/release_keys.tsv: all 804 keys, shapes scaled down consistently, random fp16
values): it imports (safetensors and .pt, `module.` prefix stripped and reported, the 201
training-only tensors skipped), the exported graphs agree with the PyTorch network, and one
missing, one misshaped and one renamed key each give an error naming the key, exit status 2 and
no output folder."""

from __future__ import annotations

import json
import struct

import numpy as np
import onnx
import pytest
import torch

from silk_export.onnx import decode as onnx_decode
from silk_export.cli import main
from silk_export.json_io import dumps
from silk_export.official.checkpoint import load_official

# Release size -> test size. D = C = H·dh = 1024 -> 32 (H 16 -> 2, dh 64 -> 16), W = 768 -> 24
# (12 heads of 2), every multiple of them alike; positions 10240 -> 256. 4 memory slots, 257
# queries, 54 point features and 10269 vocabulary rows stay.
SCALE = {1024: 32, 768: 24, 1536: 48, 2304: 72, 3072: 96, 4096: 128, 8192: 256, 16: 2, 64: 16, 128: 4, 10240: 256}


def release_layout(shared) -> list[tuple[str, list[int], bool]]:
    path = shared / "official-model" / "release_keys.tsv"
    if not path.exists():
        pytest.skip(f"no {path}")
    rows = []
    for line in path.read_text().splitlines()[1:]:
        key, shape, _dtype, _sub, used = line.split("\t")
        rows.append((key, [SCALE.get(int(d), int(d)) for d in shape.split("x")], used == "yes"))
    return rows


def random_state(layout, seed=0) -> dict[str, torch.Tensor]:
    g = torch.Generator().manual_seed(seed)
    return {k: (torch.randn(shape, generator=g) * 0.2).to(torch.float16) for k, shape, _ in layout}


def write_safetensors(path, tensors: dict[str, torch.Tensor]) -> None:
    """Minimal safetensors writer (F16/F32): header JSON, then the raw little-endian data."""
    header, blobs, offset = {"__metadata__": {"format": "pt"}}, [], 0
    for name, t in tensors.items():
        data = t.contiguous().numpy().tobytes()
        dtype = {torch.float16: "F16", torch.float32: "F32"}[t.dtype]
        header[name] = {"dtype": dtype, "shape": list(t.shape), "data_offsets": [offset, offset + len(data)]}
        blobs.append(data)
        offset += len(data)
    head = dumps(header).encode()
    head += b" " * (-len(head) % 8)
    with open(path, "wb") as f:
        f.write(struct.pack("<Q", len(head)) + head)
        for b in blobs:
            f.write(b)


@pytest.fixture(scope="module")
def layout(shared):
    return release_layout(shared)


@pytest.fixture(scope="module")
def state(layout):
    return random_state(layout)


@pytest.fixture(scope="module")
def checkpoint(state, tmp_path_factory):
    path = tmp_path_factory.mktemp("ckpt") / "model.safetensors"
    write_safetensors(path, state)
    return path


def test_layout_is_the_release(layout):
    assert len(layout) == 804 and sum(used for *_, used in layout) == 603


@pytest.fixture(scope="module")
def imported(checkpoint, tmp_path_factory):
    parent = tmp_path_factory.mktemp("imported")
    rc = main(
        [
            "import-official",
            str(checkpoint),
            "-o",
            str(parent / "model"),
            "--precision",
            "auto",
            "--no-progress",
            "--fidelity-tokens",
            "4",
        ]
    )
    assert rc == 0
    assert [p.name for p in parent.iterdir()] == ["model"]  # the temporary folder is gone
    return parent / "model"


def test_imports_and_graphs_agree_with_pytorch(checkpoint, imported):
    out = imported
    meta = json.loads((out / "model.json").read_text())
    load = meta["import"]["load"]
    assert (load["tensors"], load["used"], load["skipped_unused"]) == (804, 603, 201)
    assert load["source_dtypes"] == {"float16": 603} and load["stripped_prefixes"] == {}
    assert meta["dims"] == {
        "d_model": 32,
        "n_layers": 24,
        "n_heads": 2,
        "head_dim": 16,
        "n_latents": 261,
        "n_points": 4096,
        "max_seq_len": 257,
    }
    files = meta["files"]
    assert {files["decoder_int8"], files["decoder_int4"]} == {"decoder.int8.onnx", "decoder.int4.onnx"}
    assert files["default_decoder"] in ("decoder", "decoder_int8", "decoder_int4")
    assert set(meta["import"]["fidelity"]) == {"decoder", "decoder_int8", "decoder_int4"}
    # The graphs compute what the PyTorch network computes from the same file.
    model, _ = load_official(checkpoint, progress=False)
    points = np.random.default_rng(1).uniform(-1, 1, (1, 4096, 6)).astype(np.float32)
    ids = [10269, 0, 5, 300, 700, 5700, 6200, 10000, 2]
    with torch.no_grad():
        ref = model(torch.tensor([ids]), torch.from_numpy(points))[0].numpy()
    cross = onnx_decode.session(out / "encoder.onnx").run(None, {"points": points})[0]
    got = onnx_decode.teacher_forced(onnx_decode.session(out / "decoder.onnx"), cross, ids)
    assert np.abs(got - ref).max() <= 1e-4


def test_pt_file_with_module_prefix(state, tmp_path, capsys):
    path = tmp_path / "model.pt"
    torch.save({"module." + k: v for k, v in state.items()}, path)
    model, report = load_official(path, progress=False)
    assert report.stripped_prefixes == {"module.": 804} and report.used == 603
    assert torch.equal(model.to_logits.bias, state["to_logits.bias"].float())
    assert torch.equal(model.layers[23].cross_attn.mem_k, state["decoder.layers.70.1.mem_k"].float())


def broken(state, how):
    s = dict(state)
    if how == "missing":
        del s["decoder.layers.40.1.to_v.weight"]
    elif how == "misshaped":
        s["decoder.layers.9.0.0.weight"] = torch.zeros(31, dtype=torch.float16)
    else:
        s["to_logit.bias"] = s.pop("to_logits.bias")
    return s


@pytest.mark.parametrize(
    "how, message",
    [
        ("missing", "missing key 'decoder.layers.40.1.to_v.weight'"),
        ("misshaped", "key 'decoder.layers.9.0.0.weight': shape [31], expected [32]"),
        ("renamed", "unknown key 'to_logit.bias'"),
    ],
)
def test_bad_checkpoint_is_an_error_naming_the_key(state, tmp_path, capsys, how, message):
    path = tmp_path / "bad.safetensors"
    write_safetensors(path, broken(state, how))
    out = tmp_path / "model"
    assert main(["import-official", str(path), "-o", str(out), "--no-progress"]) == 2
    err = capsys.readouterr().err
    assert message in err
    if how == "renamed":
        assert "missing key 'to_logits.bias'" in err
    assert sorted(p.name for p in tmp_path.iterdir()) == ["bad.safetensors"]


@pytest.mark.parametrize(
    "damage, message",
    [
        (lambda b: b[:5], "too short"),
        (lambda b: struct.pack("<Q", 1 << 40) + b[8:], "header length"),
        (lambda b: b[:8] + b"{" * 8 + b[16:], "not JSON"),
        (lambda b: b.replace(b'"F16"', b'"I64"', 1), "dtype I64 is not supported"),
        (lambda b: b[:-2], "do not fit"),
    ],
)
def test_damaged_safetensors_is_a_clear_error(tmp_path, damage, message):
    from silk_export.official.state_dict_file import StateDictError, open_state_dict

    good = tmp_path / "good.safetensors"
    write_safetensors(good, {"a": torch.ones(3, dtype=torch.float16), "b": torch.ones(2, 2, dtype=torch.float16)})
    bad = tmp_path / "bad.safetensors"
    bad.write_bytes(damage(good.read_bytes()))
    with pytest.raises(StateDictError, match=message):
        open_state_dict(bad)
    assert torch.equal(open_state_dict(good).read("b"), torch.ones(2, 2, dtype=torch.float16))


def write_cloud_ply(path, points: np.ndarray) -> None:
    head = f"ply\nformat binary_little_endian 1.0\nelement vertex {len(points)}\n"
    head += "".join(f"property float {a}\n" for a in ("x", "y", "z", "nx", "ny", "nz")) + "end_header\n"
    path.write_bytes(head.encode() + np.ascontiguousarray(points, dtype="<f4").tobytes())


@pytest.mark.parametrize(
    "decoder,kv", [("fp32", "fp32"), ("fp32", "fp16"), ("fp32", "int8"), ("int4", "fp32"), ("int4", "int8")]
)
def test_libsilk_generates_64_tokens_like_the_python_loop(imported, generate_unconstrained, tmp_path, decoder, kv):
    """The C++ runtime on the imported release-layout model: 64 greedy ids from raw points, equal
    to the Python onnxruntime loop over the same graph (the fp32 or INT4 decoder, or its
    fp16/int8-cache variant, whose ai.silk ops Python's onnxruntime runs from libsilk; the INT4
    variant's weights go through Int4MatMul)."""
    import json
    import subprocess

    points = np.random.default_rng(2).uniform(-0.9, 0.9, (4096, 6)).astype(np.float32)
    write_cloud_ply(tmp_path / "points.ply", points)
    out = tmp_path / "ids.txt"
    r = subprocess.run(
        [
            str(generate_unconstrained),
            str(tmp_path / "points.ply"),
            "--model",
            str(imported),
            "--raw-points",
            "--temperature",
            "0",
            "--max-tokens",
            "64",
            "--decoder",
            decoder,
            "--kv-precision",
            kv,
            "--threads",
            "1",
            "--tokens",
            str(out),
        ],
        capture_output=True,
        text=True,
        timeout=300,
    )
    assert r.returncode == 0, r.stderr
    got = [int(x) for x in out.read_text().split()]
    files = json.loads((imported / "model.json").read_text())["files"]
    key = "decoder" if decoder == "fp32" else f"decoder_{decoder}"
    graph = files[key] if kv == "fp32" else files[f"kv_{kv}"][key]
    ops = {n.op_type for n in onnx.load(str(imported / graph), load_external_data=False).graph.node}
    assert ("CrossAttention" in ops) == (kv != "fp32")
    if decoder == "int4":
        assert ("Int4MatMul" in ops) == (kv != "fp32") and ("MatMulNBits" in ops) == (kv == "fp32")
    cross = onnx_decode.session(imported / "encoder.onnx").run(None, {"points": points[None]})[0]
    want = onnx_decode.greedy(onnx_decode.session(imported / graph), cross, 10269, 10267, 64)
    assert got == want and len(got) == 64


@pytest.mark.parametrize("suffix", [".safetensors", ".pt"])
def test_nonfinite_weights_are_refused_naming_the_key(state, tmp_path, capsys, suffix):
    """One NaN in one tensor, three Inf in another: exit 2, both keys and counts named, and no
    output folder (no model.json with a bare NaN, which is not JSON)."""
    s = dict(state)
    nan_key, inf_key = "decoder.layers.40.1.to_v.weight", "to_logits.bias"
    s[nan_key] = s[nan_key].clone()
    s[nan_key].view(-1)[5] = float("nan")
    s[inf_key] = s[inf_key].clone()
    s[inf_key][:3] = torch.tensor([float("inf"), float("-inf"), float("inf")], dtype=s[inf_key].dtype)
    path = tmp_path / f"bad{suffix}"
    if suffix == ".pt":
        torch.save(s, path)
    else:
        write_safetensors(path, s)
    out = tmp_path / "model"
    assert (
        main(
            [
                "import-official",
                str(path),
                "-o",
                str(out),
                "--no-progress",
                "--precision",
                "fp32",
                "--fidelity-tokens",
                "1",
            ]
        )
        == 2
    )
    err = capsys.readouterr().err
    assert "non-finite" in err
    assert f"key '{nan_key}': 1 NaN" in err
    assert f"key '{inf_key}': 3 Inf" in err
    assert sorted(p.name for p in tmp_path.iterdir()) == [path.name]
