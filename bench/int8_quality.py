#!/usr/bin/env python3
"""Quality loss of the INT8 decoder (dynamic quantization of the weight MatMuls) against fp32,
teacher-forced on real token sequences: for each model folder, the official tokens of dev-corpus
meshes (../shared/spec/golden-dev) with points sampled from the meshes themselves, first
`--tokens` ids, one chunk each through decoder.onnx and decoder.int8.onnx (unshared caches).

Prints per model: max and mean |Δlogit|, logit correlation, top-1 agreement, mean KL(fp32 ||
int8) of the next-token distributions, and the negative log-likelihood (nats/token) of the true
next tokens under each (meaningful for a trained model; random-weight bench models only show
the numeric error).

    SILK_LIBRARY=build/engine/libsilk.so python3 bench/int8_quality.py MODEL_DIR... [--meshes 8] [--tokens 512]
"""
from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPO / "export"))

import numpy as np  # noqa: E402
import onnxruntime as ort  # noqa: E402

from silk_export import libsilk  # noqa: E402
from silk_export.geometry import normalize_vertices  # noqa: E402
from silk_export.pointcloud import point_cloud  # noqa: E402


def session(path: Path, threads: int) -> ort.InferenceSession:
    so = ort.SessionOptions()
    so.intra_op_num_threads = threads
    return ort.InferenceSession(str(path), so, providers=["CPUExecutionProvider"])


def logits_of(dec, meta, ids: np.ndarray, cross: np.ndarray) -> np.ndarray:
    d = meta["dims"]
    t = ids.shape[1]
    feeds = {"input_ids": ids, "positions": np.arange(t, dtype=np.int64)[None],
             "seqlens_k": np.array([t - 1], np.int32), "total_sequence_length": np.array(t, np.int32)}
    empty = np.zeros((1, d["n_heads"], 0, d["head_dim"]), np.float32)
    for l in range(d["n_layers"]):
        for j, kv in enumerate(("key", "value")):
            feeds[f"past_{kv}_{l}"] = empty
            feeds[f"cross_{kv}_{l}"] = np.ascontiguousarray(cross[l, j][None])
    return dec.run(["logits"], feeds)[0][0].astype(np.float64)


def log_softmax(x: np.ndarray) -> np.ndarray:
    x = x - x.max(axis=-1, keepdims=True)
    return x - np.log(np.exp(x).sum(axis=-1, keepdims=True))


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("models", nargs="+")
    ap.add_argument("--shared", default=str(REPO.parent / "shared"))
    ap.add_argument("--meshes", type=int, default=8)
    ap.add_argument("--tokens", type=int, default=512)
    ap.add_argument("--threads", type=int, default=2)
    a = ap.parse_args()
    shared = Path(a.shared)
    names = sorted(p.name[:-len(".tokens.txt")] for p in (shared / "spec/golden-dev").glob("*.tokens.txt"))
    names = [n for n in names if (shared / "corpus/dev" / f"{n}.obj").exists()]
    step = max(1, len(names) // a.meshes)
    names = names[::step][:a.meshes]
    rng = np.random.default_rng(0)
    inputs = []
    for n in names:
        v, f = libsilk.load_arrays(shared / "corpus/dev" / f"{n}.obj")
        pts = point_cloud(normalize_vertices(v), f, rng, noise=False)
        toks = np.loadtxt(shared / "spec/golden-dev" / f"{n}.tokens.txt", dtype=np.int64).ravel()
        inputs.append((n, pts, toks))
    for model_dir in map(Path, a.models):
        meta = json.loads((model_dir / "model.json").read_text())
        if "decoder_int8" not in meta["files"]:
            print(f"{model_dir}: no INT8 decoder")
            continue
        enc = session(model_dir / meta["files"]["encoder"], a.threads)
        fp32 = session(model_dir / meta["files"]["decoder"], a.threads)
        int8 = session(model_dir / meta["files"]["decoder_int8"], a.threads)
        cap = min(a.tokens, meta["dims"]["max_seq_len"] - 1)
        stats = {"max": 0.0, "abs": [], "corr": [], "top1": [], "kl": [], "nll32": [], "nll8": []}
        for n, pts, toks in inputs:
            cross = enc.run(None, {"points": pts[None]})[0]
            seq = toks[:cap]
            ids = np.concatenate([[meta["vocab"]["bos_id"]], seq[:-1]])[None].astype(np.int64)
            l32, l8 = logits_of(fp32, meta, ids, cross), logits_of(int8, meta, ids, cross)
            diff = np.abs(l32 - l8)
            stats["max"] = max(stats["max"], float(diff.max()))
            stats["abs"].append(float(diff.mean()))
            stats["corr"].append(float(np.corrcoef(l32.ravel(), l8.ravel())[0, 1]))
            stats["top1"].append(float((l32.argmax(-1) == l8.argmax(-1)).mean()))
            p32, p8 = log_softmax(l32), log_softmax(l8)
            stats["kl"].append(float((np.exp(p32) * (p32 - p8)).sum(-1).mean()))
            rows = np.arange(len(seq))
            stats["nll32"].append(float(-p32[rows, seq].mean()))
            stats["nll8"].append(float(-p8[rows, seq].mean()))
        m = {k: (v if k == "max" else float(np.mean(v))) for k, v in stats.items()}
        print(f"{model_dir.name:>8} ({meta['config']}, {len(inputs)} dev meshes x {cap} ids): max |dlogit| "
              f"{m['max']:.3f}, mean |dlogit| {m['abs']:.4f}, corr {m['corr']:.6f}, top-1 agreement "
              f"{100 * m['top1']:.1f}%, KL(fp32||int8) {m['kl']:.5f} nats, NLL fp32 {m['nll32']:.3f} / int8 "
              f"{m['nll8']:.3f} nats/token")
    return 0


if __name__ == "__main__":
    sys.exit(main())
