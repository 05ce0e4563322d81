"""Writes a model folder per docs/model_contract.md: encoder.onnx, decoder.onnx (dynamic T, P,
N), decoder.int8.onnx (dynamic INT8 MatMul quantization) and the model.json sidecar."""
from __future__ import annotations

import json
import warnings
from pathlib import Path

import torch

from . import __version__
from .onnx_graphs import DecoderGraph, EncoderGraph, decoder_input_names, decoder_output_names
from .model import SilkModel
from .vocab import load_vocab

OPSET = 17
MODEL_VERSION = 2


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
    seqlens_k = torch.tensor([p + t - 1], dtype=torch.int32)
    total = torch.tensor(p + t, dtype=torch.int32)
    past = [torch.randn(1, c.n_heads, p, c.head_dim) for _ in range(2 * c.n_layers)]
    cross = [torch.randn(1, c.n_heads, c.n_latents, c.head_dim) for _ in range(2 * c.n_layers)]
    in_names, out_names = decoder_input_names(c.n_layers), decoder_output_names(c.n_layers)
    axes = {"input_ids": {1: "T"}, "positions": {1: "T"}, "logits": {1: "T"}}
    axes.update({name: {2: "C"} for name in in_names if name.startswith("past_")})
    axes.update({name: {2: "C_present"} for name in out_names if name.startswith("present_")})
    torch.onnx.export(DecoderGraph(model), (ids, pos, seqlens_k, total, *past, *cross), str(path),
                      input_names=in_names, output_names=out_names, dynamic_axes=axes,
                      opset_version=OPSET, custom_opsets={"com.microsoft": 1}, do_constant_folding=True,
                      dynamo=False)


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
