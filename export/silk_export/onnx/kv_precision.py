# SPDX-License-Identifier: MIT
"""The fp16 and int8 self-K/V variants of a decoder graph (docs/model_contract.md, "KV precision"):
the same weights and computation, except that each layer's self-attention keeps its
past_*/present_* caches in float16 (a step reads half the cache bytes) or in int8 rows
[1, H, C, D + 4] (D int8 values + the row's float32 scale: about a quarter). Made by rewriting an
exported decoder (fp32, INT8 or INT4 alike) instead of re-tracing it. The int8 variant has only
the "silk" form below (onnxruntime's GroupQueryAttention takes no int8 cache). fp16, two forms:
- "silk" (the default): each GroupQueryAttention becomes libsilk's ai.silk CachedAttention (same
  inputs, outputs and attributes; q, k, v stay float32 and only the cache is float16). onnxruntime
  1.22's CPU GroupQueryAttention widens the whole float16 prefix to float32 on every call, which
  costs more than the halved reads save; CachedAttention reads each cached row once. The graph
  runs in libsilk, or in Python's onnxruntime with libsilk registered as its custom-op library.
- "ort": q, k, v are cast to float16 around an unchanged GroupQueryAttention: plain onnxruntime
  runs it, slower (kept for comparison and for runtimes without libsilk).
In the "silk" form each layer's attention over the point cloud also becomes libsilk's
CrossAttention (cross_attention.py; its cross_* inputs float16), the INT4 decoder's MatMulNBits
nodes libsilk's Int4MatMul (same weights, read at memory speed; int4_matmul.py) unless
`int4="ort"` keeps them, the logits head float16 weights in libsilk's HalfMatMul
(half_logits.py), and the graph's shape arithmetic is folded into constants first
(shape_folding.py: a few thousand tiny nodes fewer per call in the release decoder (3,487 of
4,901), the same results bit for bit). A graph with external data keeps pointing at the same
`.data` file, so the variant of the 1.94 GB release decoder adds about 1 MB, plus its float16
logits head (21 MB) in the silk form."""

from __future__ import annotations

from pathlib import Path

from .cross_attention import half_cross_inputs, to_cross_attention
from .half_logits import to_half_logits
from .int4_matmul import INT4_FORMS, to_int4_matmul
from .rows import ROWS_CONTRACT, batch_dims, wire_rows
from .shape_folding import fold_shapes
from .silk_ops import SILK_ATTENTION, SILK_DOMAIN

KV_PRECISIONS = ("fp32", "fp16", "int8")
# model.json: files.<KV_FILES[p]>[<decoder key>] = the precision-p variant of files.<decoder key>.
KV_FILES = {"fp16": "kv_fp16", "int8": "kv_int8"}
KV_FILES_KEY = KV_FILES["fp16"]
# The variant's file name: decoder.int4.onnx -> decoder.int4.<suffix>.onnx
KV_SUFFIXES = {"fp16": "kv16", "int8": "kv8"}
DECODER_KEYS = ("decoder", "decoder_int8", "decoder_int4")
ATTENTION_FORMS = ("silk", "ort")
# GroupQueryAttention attributes CachedAttention implements; any other must be absent or default.
_GQA_KEPT = {"num_heads", "kv_num_heads", "scale"}
_GQA_DEFAULTS = {"do_rotary": 0, "rotary_interleaved": 0, "local_window_size": -1, "softcap": 0.0, "smooth_softmax": 0}


def kv_name(decoder_file: str, precision: str) -> str:
    """decoder.int4.onnx -> decoder.int4.kv16.onnx (fp16), decoder.int4.kv8.onnx (int8)"""
    stem = decoder_file[: -len(".onnx")] if decoder_file.endswith(".onnx") else decoder_file
    return f"{stem}.{KV_SUFFIXES[precision]}.onnx"


def _check_precision(precision: str) -> None:
    if precision not in KV_FILES:
        raise ValueError(f"cache variant precision '{precision}': expected one of {', '.join(KV_FILES)}")


def _set_cache_type(vi, precision: str) -> None:
    """A past_*/present_* input or output to the variant's element type (int8: last dim D + 4)."""
    from onnx import TensorProto

    t = vi.type.tensor_type
    t.elem_type = TensorProto.FLOAT16 if precision == "fp16" else TensorProto.INT8
    if precision == "int8" and len(t.shape.dim) == 4:
        last = t.shape.dim[3]
        if last.HasField("dim_value"):
            last.dim_value += 4
        else:
            last.dim_param = "row_bytes"  # D + 4


def _to_cached_attention(node, src: Path) -> None:
    """Turns one GroupQueryAttention node into ai.silk CachedAttention in place."""
    from onnx import helper

    for a in node.attribute:
        if a.name not in _GQA_KEPT and helper.get_attribute_value(a) != _GQA_DEFAULTS.get(a.name, object()):
            raise ValueError(
                f"{src}: GroupQueryAttention '{node.name}' has attribute {a.name}="
                f"{helper.get_attribute_value(a)}, which CachedAttention does not implement "
                f"(use --attention ort)"
            )
    if len(node.input) != 7 or any(not n for n in node.input):
        raise ValueError(
            f"{src}: GroupQueryAttention '{node.name}' has inputs {list(node.input)}; CachedAttention "
            "takes exactly q, k, v, past_key, past_value, seqlens_k, total_sequence_length"
        )
    kept = [a for a in node.attribute if a.name in _GQA_KEPT]
    del node.attribute[:]
    node.attribute.extend(kept)
    node.op_type, node.domain = SILK_ATTENTION, SILK_DOMAIN


def _cast_around(node, rewritten: int) -> list:
    """The "ort" form: float16 casts of q, k, v before the node and of its output after it."""
    from onnx import TensorProto, helper

    before = []
    for i in range(3):  # q, k, v
        half = f"{node.input[i]}__kv16_{rewritten}"
        before.append(
            helper.make_node("Cast", [node.input[i]], [half], to=TensorProto.FLOAT16, name=f"{node.name}_kv16_in{i}")
        )
        node.input[i] = half
    out = node.output[0]
    node.output[0] = f"{out}__kv16"
    after = helper.make_node("Cast", [node.output[0]], [out], to=TensorProto.FLOAT, name=f"{node.name}_kv16_out")
    return before + [node, after]


def make_kv16_decoder(src: Path, dst: Path, attention: str = "silk") -> list[str]:
    """The fp16-cache variant (make_kv_decoder with precision "fp16")."""
    return make_kv_decoder(src, dst, "fp16", attention)


def _check_forms(precision: str, attention: str, int4: str) -> None:
    if attention not in ATTENTION_FORMS:
        raise ValueError(f"attention form '{attention}': expected one of {', '.join(ATTENTION_FORMS)}")
    if int4 not in INT4_FORMS:
        raise ValueError(f"INT4 form '{int4}': expected one of {', '.join(INT4_FORMS)}")
    if precision == "int8" and attention != "silk":
        raise ValueError(
            "the int8-cache variant exists only in the silk attention form "
            "(onnxruntime's GroupQueryAttention takes no int8 cache)"
        )
    if attention == "ort" and int4 == "silk":
        raise ValueError("the ort attention form runs without libsilk: it keeps MatMulNBits (--int4 ort)")


def _external_files(m) -> list[str]:
    """The external data files graph `m`'s tensors point at."""
    from onnx import TensorProto
    from onnx.external_data_helper import _get_all_tensors

    return sorted(
        {
            e.value
            for t in _get_all_tensors(m)
            if t.data_location == TensorProto.EXTERNAL
            for e in t.external_data
            if e.key == "location"
        }
    )


def make_kv_decoder(
    src: Path,
    dst: Path,
    precision: str = "fp16",
    attention: str = "silk",
    int4: str | None = None,
    rows: bool = False,
) -> list[str]:
    """Writes the `precision` ("fp16" or "int8") cache variant of decoder graph `src` to `dst`
    (same folder), in the given attention form ("silk" or "ort", see above; int8: "silk" only) and
    INT4 form ("silk": Int4MatMul, "ort": MatMulNBits; default: the attention form's).
    rows: a contract v4 graph (R rows per call, rows.py; the silk attention form only).
    Returns the external data files it references (those of `src`; none are copied). Raises
    ValueError when `src` has no GroupQueryAttention over past_*/present_* (not a contract decoder)."""
    import onnx
    from onnx import helper

    _check_precision(precision)
    int4 = attention if int4 is None else int4
    _check_forms(precision, attention, int4)
    if rows and attention != "silk":
        raise ValueError("contract v4 (R rows) exists only in the silk attention form")
    src, dst = Path(src), Path(dst)
    if src.parent.resolve() != dst.parent.resolve():
        raise ValueError(
            f"{dst}: the {precision}-cache variant must sit beside {src.name} (it shares its external data)"
        )
    m = onnx.load(str(src), load_external_data=False)
    g = m.graph
    if rows:
        batch_dims(g)  # before folding: the folded Reshape targets keep R and S dynamic
    if attention == "silk":
        fold_shapes(g, src.parent)
    cache_names = {i.name for i in g.input if i.name.startswith("past_")}
    cache_names |= {o.name for o in g.output if o.name.startswith("present_")}
    nodes, rewritten = [], 0
    for node in g.node:
        if node.op_type != "GroupQueryAttention" or node.domain != "com.microsoft":
            nodes.append(node)
            continue
        if not (node.input[3] in cache_names and node.input[4] in cache_names):
            raise ValueError(f"{src}: GroupQueryAttention '{node.name}' does not read past_* inputs")
        if attention == "silk":
            _to_cached_attention(node, src)
            nodes.append(node)
        else:
            nodes.extend(_cast_around(node, rewritten))
        rewritten += 1
    if not rewritten:
        raise ValueError(f"{src}: no com.microsoft GroupQueryAttention node (not a contract decoder graph)")
    del g.node[:]
    g.node.extend(nodes)
    if attention == "silk":
        to_cross_attention(g)
        half_cross_inputs(g)
    if int4 == "silk":
        to_int4_matmul(g)  # nodes it does not compute stay MatMulNBits
    if attention == "silk":
        to_half_logits(g, src.parent)
    if rows:
        wire_rows(g, src)
    if attention == "silk" and not any(o.domain == SILK_DOMAIN for o in m.opset_import):
        m.opset_import.append(helper.make_opsetid(SILK_DOMAIN, 1))
    for vi in list(g.input) + list(g.output):
        if vi.name in cache_names:
            _set_cache_type(vi, precision)
    # Intermediate type annotations of the rewritten values would now be wrong: drop them.
    stale = set(cache_names) | {n.output[0] for n in g.node if n.op_type in ("GroupQueryAttention", SILK_ATTENTION)}
    produced = {o for n in g.node for o in n.output}  # the rewrites remove some intermediate values
    # A v4 graph's intermediate shapes were traced with batch 1: dropped as well.
    kept = [vi for vi in g.value_info if vi.name not in stale and vi.name in produced and not rows]
    del g.value_info[:]
    g.value_info.extend(kept)
    data = _external_files(m)
    onnx.save(m, str(dst))  # external tensors keep their location: the variant shares src's data file
    return data


def add_kv_variants(
    folder: Path, files: dict, precision: str, attention: str = "silk", int4: str | None = None, rows: bool = False
) -> dict:
    """For every decoder named in model.json `files`: writes its `precision`-cache variant (in the
    given attention and INT4 forms; `rows`: contract v4) beside it and records it under
    files["kv_fp16"] / files["kv_int8"]. Returns that mapping."""
    _check_precision(precision)
    variants = {}
    for key in DECODER_KEYS:
        if key in files:
            name = kv_name(files[key], precision)
            make_kv_decoder(Path(folder) / files[key], Path(folder) / name, precision, attention, int4, rows)
            variants[key] = name
    files[KV_FILES[precision]] = variants
    return variants


def add_kv16_to_folder(folder: Path, default: str | None = None, attention: str = "silk") -> dict:
    """`silk-export kv16` (add_kv_to_folder with precision "fp16")."""
    return add_kv_to_folder(folder, "fp16", default, attention)


def _check_default(files: dict, default: str, adding: str) -> None:
    """files.default_kv_precision = `default` needs that variant of the default decoder: already
    in `files`, or about to be written (`adding` is the precision whose variants are)."""
    if default not in KV_PRECISIONS:
        raise ValueError(f"default KV precision '{default}': expected one of {', '.join(KV_PRECISIONS)}")
    decoder = files.get("default_decoder", "decoder")
    has = decoder in files if default == adding else decoder in files.get(KV_FILES.get(default, ""), {})
    if default != "fp32" and not has:
        raise ValueError(
            f"default KV precision '{default}' needs files.{KV_FILES[default]}.{decoder} (the default "
            f"decoder's {default}-cache variant: run silk-export {KV_SUFFIXES[default]} first)"
        )


def add_kv_to_folder(
    folder: Path,
    precision: str,
    default: str | None = None,
    attention: str = "silk",
    int4: str | None = None,
    rows: bool | None = None,
) -> dict:
    """`silk-export kv16` / `kv8`: the `precision`-cache variant of every decoder of an exported
    model folder, recorded in its model.json (files.kv_fp16 / files.kv_int8;
    files.default_kv_precision when `default` is given, and external data the variants share is
    already listed). `rows`: the variants in decoder contract v4 (R rows per call) and model.json
    model_version 4 (ROWS_CONTRACT); None: as the folder is (v4 for a model_version 4 folder, so
    its variants never mix contracts). Returns the new "files"."""
    import json
    import os

    folder = Path(folder)
    _check_precision(precision)
    path = folder / "model.json"
    try:
        meta = json.loads(path.read_text())
    except (OSError, json.JSONDecodeError) as e:
        raise ValueError(f"{path}: {e}") from None
    files = meta.setdefault("files", {"encoder": "encoder.onnx", "decoder": "decoder.onnx"})
    if default is not None:
        _check_default(files, default, precision)
    if rows is None:
        rows = meta.get("model_version", 0) >= ROWS_CONTRACT
    if rows and meta.get("model_version", 0) < 3:
        raise ValueError(
            f"{path}: model_version {meta.get('model_version')}: contract v4 needs a version 3 folder (arch, preprocessing)"
        )
    add_kv_variants(folder, files, precision, attention, int4, rows)
    if rows:
        meta["model_version"] = ROWS_CONTRACT
    if default is not None:
        files["default_kv_precision"] = default
    tmp = path.with_name(f".model.json.{os.getpid()}")
    tmp.write_text(json.dumps(meta, indent=2, allow_nan=False) + "\n")
    tmp.replace(path)
    return files
