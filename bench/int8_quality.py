#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Quality loss of the quantized decoders (INT8: dynamic quantization of the weight MatMuls; INT4:
MatMulNBits) against fp32, teacher-forced on real token sequences: for each model folder, the
official tokens of dev-corpus meshes (../shared/spec/golden-dev) with points sampled from the
meshes themselves, first `--tokens` ids, one chunk each through decoder.onnx and each quantized
decoder model.json lists (unshared caches). `--int4` also quantizes decoder.onnx to INT4 in a
temporary folder when the model has no INT4 decoder (e.g. the bundled default model), with the
importer's block size and accuracy level unless told otherwise.

Prints per model and variant: max and mean |Δlogit|, logit correlation, top-1 agreement, mean
KL(fp32 || variant) of the next-token distributions, and the negative log-likelihood (nats/token)
of the true next tokens under each (meaningful for a trained model, whose logits are not flat;
random-weight bench models only show the numeric error).

    SILK_LIBRARY=build/engine/libsilk.so python3 bench/int8_quality.py MODEL_DIR... [--int4] [--meshes 8] [--tokens 512]
"""

from __future__ import annotations

import argparse
import json
import sys
import tempfile
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPO / "export"))

import numpy as np  # noqa: E402
import onnxruntime as ort  # noqa: E402

import silk_export  # noqa: E402,F401  (puts bindings/python on the path)
import silk_mesh  # noqa: E402
from silk_export.import_official import INT4_ACCURACY_LEVEL, INT4_BLOCK_SIZE  # noqa: E402
from silk_export.onnx.export import quantize_decoder_int4  # noqa: E402
from silk_export.data.pointcloud import point_cloud  # noqa: E402


def session(path: Path, threads: int) -> ort.InferenceSession:
    so = ort.SessionOptions()
    so.intra_op_num_threads = threads
    return ort.InferenceSession(str(path), so, providers=["CPUExecutionProvider"])


def logits_of(dec, meta, ids: np.ndarray, cross: np.ndarray) -> np.ndarray:
    d = meta["dims"]
    t = ids.shape[1]
    feeds = {
        "input_ids": ids,
        "positions": np.arange(t, dtype=np.int64)[None],
        "seqlens_k": np.array([t - 1], np.int32),
        "total_sequence_length": np.array(t, np.int32),
    }
    empty = np.zeros((1, d["n_heads"], 0, d["head_dim"]), np.float32)
    for l in range(d["n_layers"]):
        for j, kv in enumerate(("key", "value")):
            feeds[f"past_{kv}_{l}"] = empty
            feeds[f"cross_{kv}_{l}"] = np.ascontiguousarray(cross[l, j][None])
    return dec.run(["logits"], feeds)[0][0].astype(np.float64)


def log_softmax(x: np.ndarray) -> np.ndarray:
    x = x - x.max(axis=-1, keepdims=True)
    return x - np.log(np.exp(x).sum(axis=-1, keepdims=True))


def load_inputs(shared: Path, n_meshes: int) -> list:
    """(name, points [N,6], official tokens) of `n_meshes` dev meshes spread over the golden set."""
    names = sorted(p.name[: -len(".tokens.txt")] for p in (shared / "spec/golden-dev").glob("*.tokens.txt"))
    names = [n for n in names if (shared / "corpus/dev" / f"{n}.obj").exists()]
    names = names[:: max(1, len(names) // n_meshes)][:n_meshes]
    rng = np.random.default_rng(0)
    inputs = []
    for n in names:
        v, f = silk_mesh.load_arrays(shared / "corpus/dev" / f"{n}.obj")
        pts = point_cloud(v, f, rng, noise=False)
        toks = np.loadtxt(shared / "spec/golden-dev" / f"{n}.tokens.txt", dtype=np.int64).ravel()
        inputs.append((n, pts, toks))
    return inputs


def variants(model_dir: Path, meta: dict, a, scratch: Path) -> dict[str, Path]:
    """Quantized decoders to compare: label -> file (INT4 made in `scratch` when asked and absent)."""
    files = meta["files"]
    out = {
        label: model_dir / files[key]
        for key, label in (("decoder_int8", "int8"), ("decoder_int4", "int4"))
        if files.get(key)
    }
    if a.int4 and "int4" not in out:
        out["int4"] = scratch / f"{model_dir.name}.decoder.int4.onnx"
        quantize_decoder_int4(model_dir / files["decoder"], out["int4"], a.int4_block_size, a.int4_accuracy_level)
    return out


def compare(enc, fp32, quant, meta: dict, inputs: list, cap: int) -> dict:
    """Mean over the meshes of each figure (max |dlogit|: the maximum)."""
    stats = {"max": 0.0, "abs": [], "corr": [], "top1": [], "kl": [], "nll32": [], "nllq": []}
    for _, pts, toks in inputs:
        cross = enc.run(None, {"points": pts[None]})[0]
        seq = toks[:cap]
        ids = np.concatenate([[meta["vocab"]["bos_id"]], seq[:-1]])[None].astype(np.int64)
        l32, lq = logits_of(fp32, meta, ids, cross), logits_of(quant, meta, ids, cross)
        diff = np.abs(l32 - lq)
        stats["max"] = max(stats["max"], float(diff.max()))
        stats["abs"].append(float(diff.mean()))
        stats["corr"].append(float(np.corrcoef(l32.ravel(), lq.ravel())[0, 1]))
        stats["top1"].append(float((l32.argmax(-1) == lq.argmax(-1)).mean()))
        p32, pq = log_softmax(l32), log_softmax(lq)
        stats["kl"].append(float((np.exp(p32) * (p32 - pq)).sum(-1).mean()))
        rows = np.arange(len(seq))
        stats["nll32"].append(float(-p32[rows, seq].mean()))
        stats["nllq"].append(float(-pq[rows, seq].mean()))
    return {k: (v if k == "max" else float(np.mean(v))) for k, v in stats.items()}


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("models", nargs="+")
    ap.add_argument("--shared", default=str(REPO.parent / "shared"))
    ap.add_argument("--meshes", type=int, default=8)
    ap.add_argument("--tokens", type=int, default=512)
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--int4", action="store_true", help="also an INT4 decoder where the model has none")
    ap.add_argument("--int4-block-size", type=int, default=INT4_BLOCK_SIZE)
    ap.add_argument("--int4-accuracy-level", type=int, default=INT4_ACCURACY_LEVEL)
    a = ap.parse_args()
    inputs = load_inputs(Path(a.shared), a.meshes)
    with tempfile.TemporaryDirectory(prefix="silk-quant-quality-") as scratch:
        for model_dir in map(Path, a.models):
            meta = json.loads((model_dir / "model.json").read_text())
            quantized = variants(model_dir, meta, a, Path(scratch))
            if not quantized:
                print(f"{model_dir}: no quantized decoder (--int4 makes one)")
                continue
            enc = session(model_dir / meta["files"]["encoder"], a.threads)
            fp32 = session(model_dir / meta["files"]["decoder"], a.threads)
            cap = min(a.tokens, meta["dims"]["max_seq_len"] - 1)
            for label, path in quantized.items():
                m = compare(enc, fp32, session(path, a.threads), meta, inputs, cap)
                print(
                    f"{model_dir.name:>8} {label} ({meta['config']}, {len(inputs)} dev meshes x {cap} ids): max "
                    f"|dlogit| {m['max']:.3f}, mean |dlogit| {m['abs']:.4f}, corr {m['corr']:.6f}, top-1 agreement "
                    f"{100 * m['top1']:.1f}%, KL(fp32||{label}) {m['kl']:.5f} nats, NLL fp32 {m['nll32']:.3f} / "
                    f"{label} {m['nllq']:.3f} nats/token"
                )
    return 0


if __name__ == "__main__":
    sys.exit(main())
