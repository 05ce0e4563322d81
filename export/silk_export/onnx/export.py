# SPDX-License-Identifier: MIT
"""Writes a model folder per docs/model_contract.md for any registered architecture:
encoder.onnx, decoder.onnx (dynamic T and cache length), optional INT8 (dynamic MatMul
quantization) and INT4 (MatMulNBits) decoders, and the model.json sidecar. Graphs over the 2 GB
protobuf limit keep their weights in one external data file `<graph>.onnx.data` beside them."""

from __future__ import annotations

import shutil
import warnings
from pathlib import Path

import torch

from .. import __version__
from ..json_io import dumps, write_json
from ..models.configs import ModelConfig
from ..models.finite import check_finite
from ..registry import get_architecture
from ..vocab import load_vocab
from .kv_precision import KV_FILES, add_kv_variants
from .rows import ROWS_CONTRACT
from .graphs import DecoderGraph, EncoderGraph, decoder_input_names, decoder_output_names

OPSET = 17
DATA_ALIGN = 4096


def gather_external_data(path: Path) -> list[str]:
    """torch.onnx.export writes a graph over 2 GB with one file per tensor next to it; this streams
    them into `<name>.data` (one file, 4 KiB-aligned offsets) and deletes the pieces. Returns the
    external data file names ([] for a self-contained graph)."""
    import onnx
    from onnx.external_data_helper import ExternalDataInfo, _get_all_tensors, set_external_data

    m = onnx.load(str(path), load_external_data=False)
    tensors = [t for t in _get_all_tensors(m) if t.data_location == onnx.TensorProto.EXTERNAL]
    if not tensors:
        return []
    data_name = path.name + ".data"
    pieces = set()
    with open(path.parent / data_name, "wb") as out:
        for t in tensors:
            info = ExternalDataInfo(t)
            src = path.parent / info.location
            pieces.add(src)
            offset = -(-out.tell() // DATA_ALIGN) * DATA_ALIGN
            out.seek(offset)
            with open(src, "rb") as f:
                f.seek(info.offset or 0)
                length = _copy(f, out, info.length)
            set_external_data(t, data_name, offset=offset, length=length)
    onnx.save(m, str(path))
    for p in pieces:
        if p.name != data_name:
            p.unlink()
    return [data_name]


def _copy(src, dst, length: int | None) -> int:
    n = 0
    while length is None or n < length:
        chunk = src.read(1 << 24 if length is None else min(1 << 24, length - n))
        if not chunk:
            break
        dst.write(chunk)
        n += len(chunk)
    return n


def write_weights_external(path: Path, module: torch.nn.Module) -> list[str]:
    """For a graph exported with export_params=False (its weights are graph inputs named by the
    module's state_dict keys): streams each weight into `<name>.data` and turns the input into an
    initializer stored there. Only one tensor is ever copied at a time."""
    import onnx

    m = onnx.load(str(path))
    state = module.state_dict(keep_vars=True)
    data_name = path.name + ".data"
    inputs = []
    with open(path.parent / data_name, "wb") as out:
        for inp in m.graph.input:
            t = state.get(inp.name)
            if t is None:
                inputs.append(inp)
                continue
            arr = t.detach().float().contiguous().numpy()
            offset = -(-out.tell() // DATA_ALIGN) * DATA_ALIGN
            out.seek(offset)
            out.write(memoryview(arr).cast("B"))
            tensor = onnx.TensorProto(
                name=inp.name, data_type=onnx.TensorProto.FLOAT, dims=arr.shape, data_location=onnx.TensorProto.EXTERNAL
            )
            for key, value in (("location", data_name), ("offset", offset), ("length", arr.nbytes)):
                entry = tensor.external_data.add()
                entry.key, entry.value = key, str(value)
            m.graph.initializer.append(tensor)
    del m.graph.input[:]
    m.graph.input.extend(inputs)
    onnx.save(m, str(path))
    return [data_name]


def export_graph(module: torch.nn.Module, args: tuple, path: Path, external: bool = False, **kwargs) -> list[str]:
    """torch.onnx.export into an empty folder of its own (a large graph's per-tensor files must not
    meet another graph's), then moved to `path`. Returns its external data file names.

    external: weights go to `<name>.data` without ever being serialised into one protobuf (the
    exporter's in-memory copies of a 2 GB graph would need ~6 GB more); no constant folding then
    (the weights are not constants while tracing), so use it with pre-transposed Linears
    (transpose_linears) and let onnxruntime fold the rest at load."""
    work = path.parent / f".{path.name}.export"
    shutil.rmtree(work, ignore_errors=True)
    work.mkdir(parents=True)
    try:
        with torch.no_grad(), warnings.catch_warnings():
            warnings.simplefilter("ignore")  # tracer warnings about shape-dependent Python values
            torch.onnx.export(
                module,
                args,
                str(work / path.name),
                opset_version=OPSET,
                do_constant_folding=not external,
                export_params=not external,
                dynamo=False,
                **kwargs,
            )
        if external:
            data = write_weights_external(work / path.name, module)
            if len(onnx_inputs(work / path.name)) != len(kwargs["input_names"]):
                raise RuntimeError(f"{path.name}: weights left as graph inputs after the external export")
        else:
            data = gather_external_data(work / path.name)
        for name in [path.name, *data]:
            (work / name).replace(path.parent / name)
        return data
    finally:
        shutil.rmtree(work, ignore_errors=True)


class TransposedLinear(torch.nn.Module):
    """nn.Linear with its weight stored as [in, out]: exported as MatMul on the initializer itself,
    so constant folding makes no transposed copy of every weight (2 GB at the release size)."""

    def __init__(self, linear: torch.nn.Linear):
        super().__init__()
        self.weight_t = torch.nn.Parameter(linear.weight.detach().t().contiguous(), requires_grad=False)
        self.bias = linear.bias

    def forward(self, x: torch.Tensor) -> torch.Tensor:
        y = torch.matmul(x, self.weight_t)
        return y if self.bias is None else y + self.bias


def transpose_linears(model: torch.nn.Module) -> torch.nn.Module:
    """In place, one layer at a time (never two copies of all weights): every nn.Linear becomes a
    TransposedLinear computing the same. For a model that is exported and then dropped."""
    for module in list(model.modules()):
        for name, child in list(module.named_children()):
            if type(child) is torch.nn.Linear:
                setattr(module, name, TransposedLinear(child))
    return model


def onnx_inputs(path: Path) -> list[str]:
    import onnx

    return [i.name for i in onnx.load(str(path), load_external_data=False).graph.input]


def export_encoder(model, path: Path, fixed_points: bool = False) -> list[str]:
    """fixed_points: the point count is cfg.n_points in the graph (contract v3), else dynamic."""
    n = model.cfg.n_points if fixed_points else 128
    axes = {} if fixed_points else {"points": {1: "n_points"}}
    return export_graph(
        EncoderGraph(model),
        (torch.randn(1, n, 6),),
        path,
        input_names=["points"],
        output_names=["cross_kv"],
        dynamic_axes=axes,
    )


def export_decoder(model, path: Path, external: bool = False) -> list[str]:
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
    return export_graph(
        DecoderGraph(model),
        (ids, pos, seqlens_k, total, *past, *cross),
        path,
        external,
        input_names=in_names,
        output_names=out_names,
        dynamic_axes=axes,
        custom_opsets={"com.microsoft": 1},
    )


def int8_unsafe_matmuls(path: Path) -> list[str]:
    """Weight MatMuls whose output width is not a multiple of 16 (the 10269-wide logits head).
    onnxruntime 1.22.1's single-threaded MatMulInteger gets the last columns wrong for such
    widths on every 32nd row (found by the int8 parity test), so those stay fp32."""
    import onnx

    m = onnx.load(str(path), load_external_data=False)
    shapes = {i.name: list(i.dims) for i in m.graph.initializer}
    return [
        n.name
        for n in m.graph.node
        if n.op_type == "MatMul" and n.input[1] in shapes and shapes[n.input[1]][-1] % 16 != 0
    ]


def logits_head_matmuls(path: Path) -> list[str]:
    """The weight MatMul(s) producing the 10269 logits."""
    import onnx

    m = onnx.load(str(path), load_external_data=False)
    shapes = {i.name: list(i.dims) for i in m.graph.initializer}
    width = load_vocab().model_vocab_size
    return [n.name for n in m.graph.node if n.op_type == "MatMul" and shapes.get(n.input[1], [0])[-1] == width]


def int4_unblocked_matmuls(path: Path, block_size: int) -> list[str]:
    """The weight MatMuls whose K is not a multiple of `block_size`: MatMulNBits would pad them,
    libsilk's Int4MatMul does not compute them, and onnxruntime's MatMulNBits is not row-exact on
    every CPU (on AVX2 without AVX-512 a batch's rows differ from each row alone), so they stay
    fp32 (small by construction: K below a block or not a whole number of blocks)."""
    import onnx

    m = onnx.load(str(path), load_external_data=False)
    shapes = {i.name: list(i.dims) for i in m.graph.initializer}
    return [
        n.name
        for n in m.graph.node
        if n.op_type == "MatMul" and len(shapes.get(n.input[1], [])) == 2 and shapes[n.input[1]][0] % block_size
    ]


def quantize_decoder(src: Path, dst: Path) -> None:
    """Dynamic INT8 quantization of the weight MatMuls (activations quantized at run time)."""
    from onnxruntime.quantization import QuantType, quantize_dynamic

    quantize_dynamic(
        str(src),
        str(dst),
        op_types_to_quantize=["MatMul"],
        weight_type=QuantType.QInt8,
        per_channel=True,
        nodes_to_exclude=int8_unsafe_matmuls(src),
        use_external_data_format=has_external_data(src),
    )


def quantize_decoder_int4(src: Path, dst: Path, block_size: int = 32, accuracy_level: int = 4) -> None:
    """4-bit weight-only quantization of the weight MatMuls (com.microsoft MatMulNBits, symmetric,
    `block_size` weights per scale; accuracy_level 4 = int8 activations in the kernel). The logits
    head stays fp32: 2 % of the weights, but 4-bit noise on it moves every logit directly; so do
    MatMuls whose K is not a whole number of blocks (int4_unblocked_matmuls)."""
    import logging

    import onnx
    from onnxruntime.quantization.matmul_nbits_quantizer import MatMulNBitsQuantizer

    logging.getLogger("onnxruntime.quantization.matmul_nbits_quantizer").setLevel(logging.WARNING)  # per-node INFO
    q = MatMulNBitsQuantizer(
        onnx.load(str(src)),
        block_size=block_size,
        is_symmetric=True,
        accuracy_level=accuracy_level,
        nodes_to_exclude=logits_head_matmuls(src) + int4_unblocked_matmuls(src, block_size),
    )
    q.process()
    q.model.save_model_to_file(str(dst), use_external_data_format=False)


def has_external_data(path: Path) -> bool:
    return (path.parent / (path.name + ".data")).exists()


def sidecar(
    cfg: ModelConfig, training: dict, files: dict, extra: dict | None = None, model_version: int | None = None
) -> dict:
    """model.json: version 2 for "silk", version 3 (arch, preprocessing, sampling) for "official";
    `model_version` 4 (contract v4 cache variants, rows.py): as the architecture's, with "arch"."""
    import onnx
    import onnxruntime

    import silk_mesh

    arch = get_architecture(cfg.arch)
    vocab = load_vocab()
    try:
        lib_version = silk_mesh.version()
    except OSError:
        lib_version = None
    version = model_version or arch.model_version
    meta = {"format": "silk-model", "model_version": version}
    if version >= 3:
        meta["arch"] = arch.name
    meta.update(
        {
            "token_format": vocab.layout["token_format"],
            "token_format_version": vocab.layout["token_format_version"],
            "config": cfg.name,
            "vocab": vocab.sidecar(),
            "dims": {
                "d_model": cfg.d_model,
                "n_layers": cfg.n_layers,
                "n_heads": cfg.n_heads,
                "head_dim": cfg.head_dim,
                "n_latents": cfg.n_latents,
                "n_points": cfg.n_points,
                "max_seq_len": cfg.max_seq_len,
            },
            "normalize_bound": 0.95,
        }
    )
    if arch.model_version >= 3:  # a "silk" folder keeps its defaults (docs/model_contract.md)
        meta["preprocessing"] = arch.preprocessing(cfg)
        meta["sampling"] = dict(arch.sampling)
    meta["files"] = files
    meta.update(extra or {})
    meta["training"] = training
    meta["versions"] = {
        "silk_export": __version__,
        "libsilk": lib_version,
        "torch": torch.__version__,
        "onnx": onnx.__version__,
        "onnxruntime": onnxruntime.__version__,
        "opset": OPSET,
    }
    return meta


def decoder_weight_bytes(model) -> int:
    """fp32 bytes of what the decoder graph holds (everything but the point encoder)."""
    skip = {id(p) for name, p in model.named_parameters() if "encoder" in name}
    return 4 * sum(p.numel() for p in model.parameters() if id(p) not in skip)


def export_graphs(model, out_dir: Path, external_over: int = 1 << 30) -> dict:
    """encoder.onnx + decoder.onnx (fp32) into out_dir; returns model.json "files". A decoder
    holding more than `external_over` bytes of weights is written with external data (see
    export_graph; the release-size official decoder: 1.94 GB)."""
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    model = model.float().eval()
    fixed_points = get_architecture(model.cfg.arch).model_version >= 3
    data = export_encoder(model, out_dir / "encoder.onnx", fixed_points)
    data += export_decoder(model, out_dir / "decoder.onnx", decoder_weight_bytes(model) > external_over)
    files = {"encoder": "encoder.onnx", "decoder": "decoder.onnx"}
    if data:
        files["external_data"] = data
    return files


def _check_kv_choice(variants: tuple[str, ...], default: str | None) -> None:
    """The cache variants an export writes exist, and the default cache is fp32 or one of them."""
    for v in variants:
        if v not in KV_FILES:
            raise ValueError(f"KV cache variant '{v}': expected one of {', '.join(KV_FILES)}")
    if default is not None and default != "fp32" and default not in variants:
        written = ", ".join(variants) or "none"
        raise ValueError(f"default KV precision '{default}' needs its cache variant (written: {written})")


def export_model(
    model,
    out_dir: Path,
    training: dict | None = None,
    int8: bool = True,
    sampling: dict | None = None,
    rows: bool = True,
    kv_variants: tuple[str, ...] = ("fp16", "int8"),
    kv_default: str | None = None,
) -> dict:
    """Exports all files into out_dir; returns the sidecar dict that was written. `sampling`: the
    model.json "sampling" defaults silkgen and the C API start from (absent: libsilk's built-in
    ones, temperature 0.5 and top-k 50). `rows`: model_version 4, with the `kv_variants` cache
    variants (fp16, int8) of every decoder in contract v4 (rows.py); False: the architecture's
    version and no variants (the committed test model's form). `kv_default`: files.default_kv_precision
    (None: absent, the fp32 cache). Raises ValueError before writing anything when a weight is
    NaN / Inf (naming its key), a sampling value is not finite or `kv_default` names a cache
    that is not written."""
    out_dir = Path(out_dir)
    check_finite(model.state_dict().items(), "model")
    dumps({"sampling": sampling}, what="model.json")  # a NaN default: refused before the graphs
    variants = tuple(kv_variants) if rows else ()
    _check_kv_choice(variants, kv_default)
    files = export_graphs(model, out_dir)
    if int8:
        quantize_decoder(out_dir / "decoder.onnx", out_dir / "decoder.int8.onnx")
        files["decoder_int8"] = "decoder.int8.onnx"
    for precision in variants:  # contract v4
        add_kv_variants(out_dir, files, precision, rows=True)
    if kv_default is not None:
        files["default_kv_precision"] = kv_default
    meta = sidecar(
        model.cfg,
        training or {"steps": 0, "data": None, "seed": None},
        files,
        {"sampling": sampling} if sampling else None,
        ROWS_CONTRACT if rows else None,
    )
    write_json(out_dir / "model.json", meta)
    return meta
