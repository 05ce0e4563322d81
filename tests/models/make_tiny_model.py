#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Makes tests/models/tiny/: a deterministic random-weight model in the exact format of
docs/model_contract.md, small enough to commit (~2.4 MB with decoder.kv16.onnx and decoder.kv8.onnx, the fp16 and int8 KV cache variants), for the runtime's golden and
determinism tests. Uses export/'s model code (silk_export) with a toy configuration and
weights drawn N(0, 0.5) from a fixed seed (larger than training init, so logits have an O(1)
spread and any runtime mistake changes the sampled ids), plus output biases toward U and E.

    python3 tests/models/make_tiny_model.py [--out tests/models/tiny] [--points-ply FILE]

Also writes tests/models/golden/torus_knot_points.ply, the golden test's point-cloud input.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

REPO = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(REPO / "export"))

import numpy as np  # noqa: E402
import onnx  # noqa: E402
import torch  # noqa: E402
from onnx import helper, numpy_helper  # noqa: E402

from silk_export.json_io import dumps, write_json  # noqa: E402
from silk_export.models.configs import ModelConfig  # noqa: E402
from silk_export.models.silk_model import SilkModel  # noqa: E402
from silk_export.onnx.export import export_model  # noqa: E402
from silk_export.onnx.kv_precision import add_kv_variants  # noqa: E402
from silk_export.vocab import load_vocab  # noqa: E402

SEED = 20240611
CLOSING_BIAS = {"U": 4.0, "E": 3.0, "X": -6.0}
# Two heads of width 8 (onnxruntime's GroupQueryAttention needs a multiple of 8); d_model 16
# keeps the two 10,270 x d tables (embedding, output head) at ~330 KB each in float16.
TINY = ModelConfig(
    "test-tiny",
    d_model=16,
    n_layers=2,
    n_heads=2,
    n_latents=4,
    max_seq_len=1024,
    encoder_layers=1,
    ff_mult=2,
    fourier_freqs=2,
    n_points=256,
)


def shrink(path: Path, min_elems: int = 4096) -> None:
    """Stores the big tables compactly to keep the committed files small: float32 initializers
    as float16 + Cast, the int64 type table constant as uint8 + Cast. The graph still computes
    in float32; the model's weights simply are these float16-representable values."""
    m = onnx.load(str(path))
    g = m.graph
    casts = []
    for init in list(g.initializer):
        if init.data_type != onnx.TensorProto.FLOAT or np.prod(init.dims) < min_elems:
            continue
        arr = numpy_helper.to_array(init).astype(np.float16)
        name = init.name
        g.initializer.remove(init)
        g.initializer.append(numpy_helper.from_array(arr, name + "_f16"))
        casts.append(helper.make_node("Cast", [name + "_f16"], [name], to=onnx.TensorProto.FLOAT, name=name + "_cast"))
    nodes = casts[:]
    for node in list(g.node):
        nodes.append(node)
        if node.op_type != "Constant":
            continue
        t = node.attribute[0].t
        if t.data_type != onnx.TensorProto.INT64 or np.prod(t.dims) < min_elems:
            continue
        arr = numpy_helper.to_array(t)
        if arr.min() < 0 or arr.max() > 255:
            continue
        out = node.output[0]
        node.output[0] = out + "_u8"
        node.attribute[0].t.CopyFrom(numpy_helper.from_array(arr.astype(np.uint8), t.name))
        nodes.append(helper.make_node("Cast", [out + "_u8"], [out], to=onnx.TensorProto.INT64, name=out + "_cast"))
    del g.node[:]
    g.node.extend(nodes)
    onnx.checker.check_model(m)
    onnx.save(m, str(path))


def make(out: Path) -> dict:
    torch.manual_seed(SEED)
    model = SilkModel(TINY)
    vocab = load_vocab()
    r = vocab.layout["ranges"]
    with torch.no_grad():
        for p in model.parameters():
            p.normal_(0.0, 0.5)
        # A pure random walk almost never closes a layer (random X tokens alone push the layer
        # size toward 200); these output biases make the toy model skip X and close layers and
        # components early, so short runs end with EOS and decode to several small parts.
        for name, bias in CLOSING_BIAS.items():
            lo, hi = r[name] if name in r else (vocab.eos_id, vocab.eos_id + 1)
            model.head.bias[lo:hi] += bias
    # model_version 2 with contract v3 cache variants, as committed (the runtime's v3 tests).
    meta = export_model(model, out, {"steps": 0, "data": None, "seed": SEED}, int8=False, rows=False)
    for f in ("encoder.onnx", "decoder.onnx"):
        shrink(out / f)
    add_kv_variants(out, meta["files"], "fp16")  # decoder.kv16.onnx: the fp16 KV cache path's tests
    add_kv_variants(out, meta["files"], "int8")  # decoder.kv8.onnx: the int8 KV cache path's tests
    # Keep the committed sidecar independent of which libsilk build happened to be around.
    meta.get("versions", {}).pop("libsilk", None)
    write_json(out / "model.json", meta)
    return meta


def write_point_cloud(obj: Path, out: Path) -> None:
    """The golden test's point-cloud input: the vertices of an OBJ with area-weighted vertex
    normals, as a binary little-endian PLY (x y z nx ny nz floats, no faces)."""
    v, f = [], []
    for line in obj.read_text().splitlines():
        parts = line.split()
        if parts and parts[0] == "v":
            v.append([float(x) for x in parts[1:4]])
        elif parts and parts[0] == "f":
            f.append([int(x.split("/")[0]) - 1 for x in parts[1:4]])
    v, f = np.asarray(v, np.float64), np.asarray(f, np.int64)
    fn = np.cross(v[f[:, 1]] - v[f[:, 0]], v[f[:, 2]] - v[f[:, 0]])
    n = np.zeros_like(v)
    for k in range(3):
        np.add.at(n, f[:, k], fn)
    n /= np.linalg.norm(n, axis=1, keepdims=True)
    rows = np.hstack([v, n]).astype("<f4")
    header = (
        "ply\nformat binary_little_endian 1.0\ncomment made by tests/models/make_tiny_model.py\n"
        f"element vertex {len(rows)}\n"
        + "".join(f"property float {p}\n" for p in ("x", "y", "z", "nx", "ny", "nz"))
        + "end_header\n"
    )
    out.write_bytes(header.encode() + rows.tobytes())


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--out", default=str(REPO / "tests" / "models" / "tiny"))
    ap.add_argument(
        "--points-ply",
        default=str(REPO / "tests" / "models" / "golden" / "torus_knot_points.ply"),
        help="also write the golden point-cloud input here ('' = skip)",
    )
    a = ap.parse_args()
    if a.points_ply:
        Path(a.points_ply).parent.mkdir(parents=True, exist_ok=True)
        write_point_cloud(REPO / "samples" / "torus_knot.obj", Path(a.points_ply))
    meta = make(Path(a.out))
    sizes = {f.name: f.stat().st_size for f in sorted(Path(a.out).iterdir())}
    print(dumps({"dims": meta["dims"], "bytes": sizes}, indent=2))
    return 0


if __name__ == "__main__":
    sys.exit(main())
