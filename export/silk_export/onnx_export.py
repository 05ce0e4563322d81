"""Writes a model folder per docs/model_contract.md: encoder.onnx, decoder.onnx (dynamic T, P,
N), decoder.int8.onnx (dynamic INT8 MatMul quantization) and the model.json sidecar."""
from __future__ import annotations

import json
import warnings
from pathlib import Path

import torch

from . import __version__
from .onnx_graphs import DecoderGraph, EncoderGraph
from .model import SilkModel
from .vocab import load_vocab

OPSET = 17
MODEL_VERSION = 1


def export_encoder(model: SilkModel, path: Path) -> None:
    points = torch.randn(1, 128, 6)
    torch.onnx.export(EncoderGraph(model), (points,), str(path), input_names=["points"],
                      output_names=["cross_kv"], dynamic_axes={"points": {1: "n_points"}},
                      opset_version=OPSET, do_constant_folding=True, dynamo=False)


def export_decoder(model: SilkModel, path: Path) -> None:
    c = model.cfg
    t, p = 3, 5
    ids = torch.tensor([[model.bos_id, 0, 5700]], dtype=torch.int64)
    pos = torch.arange(p, p + t, dtype=torch.int64).unsqueeze(0)
    past = torch.randn(p, c.n_layers, 2, c.n_heads, c.head_dim)
    cross = torch.randn(c.n_layers, 2, c.n_heads, c.n_latents, c.head_dim)
    torch.onnx.export(DecoderGraph(model), (ids, pos, past, cross), str(path),
                      input_names=["input_ids", "positions", "past_kv", "cross_kv"],
                      output_names=["logits", "new_kv"],
                      dynamic_axes={"input_ids": {1: "T"}, "positions": {1: "T"}, "past_kv": {0: "P"},
                                    "logits": {1: "T"}, "new_kv": {0: "T"}},
                      opset_version=OPSET, do_constant_folding=True, dynamo=False)


def int8_unsafe_matmuls(path: Path) -> list[str]:
    """Weight MatMuls whose output width is not a multiple of 16 (the 10269-wide logits head).
    onnxruntime 1.22.1's single-threaded MatMulInteger gets the last columns wrong for such
    widths on every 32nd row (found by the int8 parity test), so those stay fp32."""
    import onnx
    m = onnx.load(str(path), load_external_data=False)
    shapes = {i.name: list(i.dims) for i in m.graph.initializer}
    return [n.name for n in m.graph.node if n.op_type == "MatMul" and n.input[1] in shapes
            and shapes[n.input[1]][-1] % 16 != 0]


def quantize_decoder(src: Path, dst: Path) -> None:
    """Dynamic INT8 quantization of the weight MatMuls (activations quantized at run time)."""
    from onnxruntime.quantization import QuantType, quantize_dynamic
    quantize_dynamic(str(src), str(dst), op_types_to_quantize=["MatMul"], weight_type=QuantType.QInt8,
                     per_channel=True, nodes_to_exclude=int8_unsafe_matmuls(src))


def sidecar(model: SilkModel, training: dict, int8: bool) -> dict:
    import onnx
    import onnxruntime

    from . import libsilk
    c = model.cfg
    vocab = load_vocab()
    try:
        lib_version = libsilk.version()
    except OSError:
        lib_version = None
    files = {"encoder": "encoder.onnx", "decoder": "decoder.onnx"}
    if int8:
        files["decoder_int8"] = "decoder.int8.onnx"
    return {
        "format": "silk-model",
        "model_version": MODEL_VERSION,
        "token_format": vocab.layout["token_format"],
        "token_format_version": vocab.layout["token_format_version"],
        "config": c.name,
        "vocab": vocab.sidecar(),
        "dims": {"d_model": c.d_model, "n_layers": c.n_layers, "n_heads": c.n_heads, "head_dim": c.head_dim,
                 "n_latents": c.n_latents, "n_points": c.n_points, "max_seq_len": c.max_seq_len},
        "normalize_bound": 0.95,
        "files": files,
        "training": training,
        "versions": {"silk_export": __version__, "libsilk": lib_version, "torch": torch.__version__,
                     "onnx": onnx.__version__, "onnxruntime": onnxruntime.__version__, "opset": OPSET},
    }


def export_model(model: SilkModel, out_dir: Path, training: dict | None = None, int8: bool = True) -> dict:
    """Exports all files into out_dir; returns the sidecar dict that was written."""
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    model = model.float().eval()
    with torch.no_grad(), warnings.catch_warnings():
        warnings.simplefilter("ignore")  # tracer warnings about shape-dependent Python values
        export_encoder(model, out_dir / "encoder.onnx")
        export_decoder(model, out_dir / "decoder.onnx")
    if int8:
        quantize_decoder(out_dir / "decoder.onnx", out_dir / "decoder.int8.onnx")
    meta = sidecar(model, training or {"steps": 0, "data": None, "seed": None}, int8)
    (out_dir / "model.json").write_text(json.dumps(meta, indent=2) + "\n")
    return meta
