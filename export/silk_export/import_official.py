# SPDX-License-Identifier: MIT
"""`silk-export import-official`: a released Mesh Silksong checkpoint -> a Silk model folder
(docs/model_contract.md v3, arch "official"). Everything is written into a temporary folder
beside the destination and renamed at the end, so a failed import leaves nothing behind."""

from __future__ import annotations

import gc
import os
import shutil
import sys
import time
from dataclasses import asdict
from pathlib import Path

from .json_io import write_json
from .official.card import write_official_card
from .official.checkpoint import load_official
from .official.state_dict_file import sha256_of
from .onnx import fidelity
from .onnx.export import (
    export_graphs,
    has_external_data,
    quantize_decoder,
    quantize_decoder_int4,
    sidecar,
    transpose_linears,
)
from .onnx.kv_precision import KV_PRECISIONS, add_kv_variants
from .onnx.rows import ROWS_CONTRACT
from .vocab import load_vocab

PRECISIONS = ("fp32", "int8", "int4", "auto")
SOURCE_LICENCE = (
    "The official Mesh Silksong code (gaochao-s/Mesh-Silksong) is MIT-licensed; the weights "
    "are published with that release: see its release page for their terms."
)
# Chosen by measurement on the release-size architecture (README "Run the released Mesh Silksong model").
INT4_BLOCK_SIZE = 32
INT4_ACCURACY_LEVEL = 4
# The imported model's KV cache precision (files.default_kv_precision), chosen by measurement:
# docs/runtime.md "KV cache precision" (bench/kv_fidelity.py and bench/time_to_mesh).
DEFAULT_KV_PRECISION = "fp16"


def _say(msg: str) -> None:
    print(f"import-official: {msg}", file=sys.stderr, flush=True)


def _variants(folder: Path, precision: str, int4_block: int, int4_accuracy: int) -> dict:
    """Writes the quantized decoders the precision asks for; returns model.json file entries."""
    files = {}
    if precision in ("int8", "auto"):
        _say("INT8 decoder (dynamic MatMul quantization)")
        quantize_decoder(folder / "decoder.onnx", folder / "decoder.int8.onnx")
        files["decoder_int8"] = "decoder.int8.onnx"
    if precision in ("int4", "auto"):
        _say(f"INT4 decoder (MatMulNBits, block {int4_block}, accuracy level {int4_accuracy})")
        quantize_decoder_int4(folder / "decoder.onnx", folder / "decoder.int4.onnx", int4_block, int4_accuracy)
        files["decoder_int4"] = "decoder.int4.onnx"
    return files


def write_variants(
    folder: Path,
    files: dict,
    cfg,
    precision: str,
    int4_block: int = INT4_BLOCK_SIZE,
    int4_accuracy: int = INT4_ACCURACY_LEVEL,
    fidelity_tokens: int = 32,
    kv_precision: str = DEFAULT_KV_PRECISION,
) -> dict:
    """After export_graphs (drop the PyTorch model first: quantization loads the fp32 graph): the
    quantized decoders `precision` asks for, their fidelity/speed figures and the default decoder,
    then the fp16- and int8-cache variants of every decoder and the default KV precision.
    Updates `files` (model.json "files"); returns the figures."""
    files.update(_variants(folder, precision, int4_block, int4_accuracy))
    for name in ("decoder.int8.onnx", "decoder.int4.onnx"):
        if has_external_data(folder / name):
            files.setdefault("external_data", []).append(name + ".data")
    variants = {k: v for k, v in files.items() if k.startswith("decoder")}
    _say(f"fidelity and speed of {', '.join(variants)} ({fidelity_tokens} greedy tokens x 2 probes)")
    vocab = load_vocab()
    figures = fidelity.measure(folder, variants, vocab.bos_id, vocab.eos_id, cfg.n_points, fidelity_tokens)
    files["default_decoder"] = (
        fidelity.choose(figures)
        if precision == "auto"
        else {"fp32": "decoder", "int8": "decoder_int8", "int4": "decoder_int4"}[precision]
    )
    if kv_precision not in KV_PRECISIONS:
        raise ValueError(f"KV precision '{kv_precision}': expected one of {', '.join(KV_PRECISIONS)}")
    _say("fp16 and int8 self-K/V cache variants of every decoder (silk-export kv16, kv8)")
    add_kv_variants(folder, files, "fp16", rows=True)  # contract v4 (R rows per call)
    add_kv_variants(folder, files, "int8", rows=True)
    files["default_kv_precision"] = kv_precision
    return figures


def import_official(
    checkpoint: Path,
    out_dir: Path,
    precision: str = "auto",
    config_path: Path | None = None,
    force: bool = False,
    progress: bool = True,
    int4_block: int = INT4_BLOCK_SIZE,
    int4_accuracy: int = INT4_ACCURACY_LEVEL,
    fidelity_tokens: int = 32,
    licence: str = SOURCE_LICENCE,
    kv_precision: str = DEFAULT_KV_PRECISION,
    hub: dict | None = None,
) -> dict:
    """Returns the model.json written. Raises StateDictError / ValueError with a message naming
    the problem (a key missing, misshaped or holding NaN / Inf; a non-finite model.json figure);
    the destination is then untouched. hub: where the checkpoint came from (official/hub.py download),
    recorded in model.json's source."""
    if precision not in PRECISIONS:
        raise ValueError(f"precision '{precision}': expected one of {', '.join(PRECISIONS)}")
    checkpoint, out_dir = Path(checkpoint), Path(out_dir)
    if out_dir.exists() and not force:
        raise ValueError(f"{out_dir} already exists (use --force to replace it)")
    t0 = time.time()
    model, report = load_official(checkpoint, config_path, progress)
    cfg = model.cfg
    _say(
        f"{report.used} tensors used, {report.skipped_unused} training-only point-encoder tensors skipped"
        + (f", prefixes stripped: {report.stripped_prefixes}" if report.stripped_prefixes else "")
    )
    out_dir.parent.mkdir(parents=True, exist_ok=True)  # e.g. a models folder used for the first time
    tmp = out_dir.parent / f".{out_dir.name}.importing-{os.getpid()}"
    shutil.rmtree(tmp, ignore_errors=True)
    try:
        _say("exporting encoder.onnx and decoder.onnx (fp32)")
        files = export_graphs(transpose_linears(model), tmp)
        del model
        gc.collect()
        figures = write_variants(tmp, files, cfg, precision, int4_block, int4_accuracy, fidelity_tokens, kv_precision)
        source = {
            "file": checkpoint.name,
            "sha256": hub["sha256"] if hub else sha256_of(checkpoint),
            "bytes": checkpoint.stat().st_size,
            "licence": licence,
        }
        if hub:
            source.update(hub=hub["hub"], url=hub["url"])
        chosen = files["default_decoder"]
        extra = {
            "source": source,
            "import": {
                "load": asdict(report),
                "precision": precision,
                "int4": {"block_size": int4_block, "accuracy_level": int4_accuracy},
                "fidelity": figures,
                "thresholds": {"min_top1": fidelity.MIN_TOP1, "max_kl_mean": fidelity.MAX_MEAN_KL},
                "seconds": None,
            },
        }
        training = {"steps": None, "data": "released checkpoint (official training)", "seed": None}
        meta = sidecar(cfg, training, files, extra, ROWS_CONTRACT)
        meta["import"]["seconds"] = round(time.time() - t0, 1)
        write_json(tmp / "model.json", meta)  # a NaN figure: an error naming the field, not invalid JSON
        write_official_card(tmp, meta)
        for f in tmp.iterdir():
            f.chmod(0o644)  # onnxruntime writes external data files 0600
        if out_dir.exists():
            shutil.rmtree(out_dir)
        tmp.replace(out_dir)
    except BaseException:
        shutil.rmtree(tmp, ignore_errors=True)
        raise
    _say(f"wrote {out_dir} (default decoder: {chosen}) in {meta['import']['seconds']} s")
    return meta
