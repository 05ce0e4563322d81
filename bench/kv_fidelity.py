#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""kv_fidelity: how far the fp16 and int8 self-K/V caches (model.json files.kv_fp16, files.kv_int8)
move a decoder from the fp32 cache, teacher-forced over long real token sequences: top-1 agreement
(all positions, and those where the fp32 top id leads by >= 0.05 logits) and KL(fp32 || variant)
of the next-id distributions at every position, overall and by depth, for each decoder asked.
The same decoder weights run with both caches, so only the cache precision differs; the sequences
(the shared golden-dev token files, truncated to the model's positions) are fed in chunks (in a
variant graph the chunk's own keys/values are stored at the cache's precision before attention, so
the numbers equal step-wise feeding).

    python3 bench/kv_fidelity.py MODEL_DIR [--decoders decoder decoder_int4] [--kv fp16 int8]
        [--tokens A.tokens.txt ...] [--max-len 4096] [--points points.npy] [--chunk 256] [--threads 2]
        [--json OUT.json] [--reference FILE]

--reference FILE (a decoder file in MODEL_DIR, one decoder key) compares the variants against that
file instead of the fp32-cache decoder: e.g. the same fp16 variant written with onnxruntime's
MatMulNBits instead of libsilk's Int4MatMul (`silk-export kv16 --int4 ort`), two graphs equal but
for float32 summation order, gives the floor that rounding noise alone puts under top-1 agreement.

Defaults: the model's default decoder; two long dev sequences; the official fixture's point cloud
(shared/official-fixture/points.npy, 4,096 rows; resampled with replacement for another count).
"""

from __future__ import annotations

import argparse
import json
import sys
import time
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPO / "export"))

import numpy as np  # noqa: E402

from silk_export.onnx.decode import DecoderState, session  # noqa: E402

SHARED = REPO.parent / "shared"
DEFAULT_TOKENS = ["structural__hele_theater_struct", "skeletal__bear_polar"]
DEPTH_BUCKETS = (0, 512, 1024, 2048, 4096, 8192, 1 << 30)


def read_tokens(path: Path) -> list[int]:
    return [int(x) for x in Path(path).read_text().split()]


def cloud(path: Path, n: int) -> np.ndarray:
    pts = np.load(path).astype(np.float32)
    if len(pts) != n:
        pts = pts[np.random.default_rng(0).integers(0, len(pts), n)]
    return pts[None]


def log_softmax(x: np.ndarray) -> np.ndarray:
    x = x.astype(np.float64)
    x = x - x.max(axis=-1, keepdims=True)
    return x - np.log(np.exp(x).sum(axis=-1, keepdims=True))


def logits(decoder_path: Path, cross: np.ndarray, ids: list[int], chunk: int, threads: int) -> np.ndarray:
    state = DecoderState(session(decoder_path, threads), cross)
    return np.concatenate([state.run(ids[i : i + chunk]) for i in range(0, len(ids), chunk)])


# A position is "decided" when the fp32 cache's top id leads the runner-up by at least this many
# logits: below it the top-1 is a near-tie (random weights give nearly flat logits), and a flip
# there changes the sampled distribution by almost nothing (see KL).
DECIDED_GAP = 0.05


def compare(ref: np.ndarray, half: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Per position: top-1 equal, KL(ref || half) in nats (PAD excluded like the sampler does),
    and whether the fp32 top-1 is decided (leads by DECIDED_GAP)."""
    ref, half = ref[:, :-1], half[:, :-1]  # the last column is PAD, never sampled
    agree = ref.argmax(-1) == half.argmax(-1)
    top2 = np.partition(ref, -2, axis=-1)[:, -2:]
    decided = (top2[:, 1] - top2[:, 0]) >= DECIDED_GAP
    kls = []
    for lo in range(0, len(ref), 512):  # float64 rows in blocks: bounded memory
        lp, lq = log_softmax(ref[lo : lo + 512]), log_softmax(half[lo : lo + 512])
        kls.append((np.exp(lp) * (lp - lq)).sum(-1))
    return agree, np.concatenate(kls), decided


def summary(agree: list[np.ndarray], kl: list[np.ndarray], decided: list[np.ndarray]) -> dict:
    """Overall figures, and by depth bucket pooling the sequences position by position."""
    a, k, d = np.concatenate(agree), np.concatenate(kl), np.concatenate(decided)
    out = {
        "positions": int(a.size),
        "top1_agreement": round(float(a.mean()), 5),
        "decided_positions": int(d.sum()),
        "top1_agreement_decided": round(float(a[d].mean()), 5) if d.any() else None,
        "kl_mean": float(f"{k.mean():.3g}"),
        "kl_max": float(f"{k.max():.3g}"),
        "by_depth": {},
    }
    for lo, hi in zip(DEPTH_BUCKETS, DEPTH_BUCKETS[1:]):
        ab = np.concatenate([x[lo:hi] for x in agree])
        if ab.size:
            kb = np.concatenate([x[lo:hi] for x in kl])
            top = max(min(hi, len(x)) for x in agree) - 1
            out["by_depth"][f"{lo}-{top}"] = {
                "positions": int(ab.size),
                "top1_agreement": round(float(ab.mean()), 5),
                "kl_mean": float(f"{kb.mean():.3g}"),
            }
    return out


def variant_file(model: Path, files: dict, key: str, kv: str) -> str:
    name = files.get(f"kv_{kv}", {}).get(key)
    if key not in files or not name:
        tool = "kv16" if kv == "fp16" else "kv8"
        raise SystemExit(f"{model}: no {key} with an {kv} KV variant (run `silk-export {tool} {model}`)")
    return name


def measure(
    model: Path,
    decoders: list[str],
    kvs: list[str],
    sequences: dict[str, list[int]],
    points: Path,
    chunk: int,
    threads: int,
    reference: str | None = None,
) -> dict:
    meta = json.loads((model / "model.json").read_text())
    files, dims, bos = meta["files"], meta["dims"], meta["vocab"]["bos_id"]
    cross = session(model / files.get("encoder", "encoder.onnx"), threads).run(
        None, {"points": cloud(points, dims["n_points"])}
    )[0]
    result = {
        "model": str(model),
        "config": meta.get("config"),
        "points": str(points),
        "chunk": chunk,
        "sequences": {k: len(v) for k, v in sequences.items()},
        "decoders": {},
    }
    if reference:
        result["reference"] = reference
    for key in decoders:
        variants = {kv: variant_file(model, files, key, kv) for kv in kvs}
        figs = {kv: ([], [], []) for kv in kvs}
        t0 = time.time()
        for name, ids in sequences.items():
            seq = [bos] + ids[: dims["max_seq_len"] - 1]
            ref = logits(model / (reference or files[key]), cross, seq, chunk, threads)
            for kv, file in variants.items():
                a, k, d = compare(ref, logits(model / file, cross, seq, chunk, threads))
                for acc, x in zip(figs[kv], (a, k, d)):
                    acc.append(x)
                print(
                    f"  {key} {kv} {name}: {len(seq)} positions, top-1 {a.mean():.4f} (decided: {a[d].mean():.4f} "
                    f"of {d.sum()}), KL mean {k.mean():.3g}",
                    flush=True,
                )
        result["decoders"][key] = {kv: summary(*figs[kv]) for kv in kvs}
        result["decoders"][key]["seconds"] = round(time.time() - t0, 1)
    return result


def report(result: dict, path: Path | None) -> None:
    """The result as JSON on stdout, and into `path` when given."""
    text = json.dumps(result, indent=1)
    if path:
        path.write_text(text + "\n")
    print(text)


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("model", type=Path)
    ap.add_argument("--decoders", nargs="+", help="model.json files keys (default: the model's default decoder)")
    ap.add_argument(
        "--kv",
        nargs="+",
        default=["fp16"],
        choices=["fp16", "int8"],
        help="cache variants to compare with the fp32 cache (default: fp16)",
    )
    ap.add_argument("--tokens", nargs="+", type=Path, help="token files (one id per line)")
    ap.add_argument("--max-len", type=int, default=4096, help="positions per sequence, BOS included")
    ap.add_argument("--points", type=Path, default=SHARED / "official-fixture" / "points.npy")
    ap.add_argument("--chunk", type=int, default=256)
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--json", type=Path)
    ap.add_argument("--reference", help="decoder file in MODEL to compare against instead of the fp32-cache decoder")
    a = ap.parse_args()
    meta = json.loads((a.model / "model.json").read_text())
    decoders = a.decoders or [meta["files"].get("default_decoder", "decoder")]
    if a.reference and (len(decoders) != 1 or not (a.model / a.reference).is_file()):
        raise SystemExit(f"--reference {a.reference}: needs one decoder key and a file in {a.model}")
    paths = a.tokens or [SHARED / "spec" / "golden-dev" / f"{n}.tokens.txt" for n in DEFAULT_TOKENS]
    sequences = {p.name.split(".")[0]: read_tokens(p)[: a.max_len - 1] for p in paths}
    report(measure(a.model, decoders, a.kv, sequences, a.points, a.chunk, a.threads, a.reference), a.json)
    return 0


if __name__ == "__main__":
    sys.exit(main())
