#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""rows_agreement: how far decoding R sequences in one decoder call (contract v4 rows) moves each
sequence's logits from decoding it alone, for decoders whose products are onnxruntime's own
operators (the fp32 and INT8 decoders' MatMul / MatMulInteger, which may group the rows of a call
differently from one row), and as a check for the ai.silk ones (INT4 decoder, fp16/int8 caches),
whose rows are bit-identical by construction. R real token sequences (the shared golden-dev
files, truncated to --positions ids after BOS) are teacher-forced one id per call, all rows
attending to one encoder output (the candidates of one mesh); each row's logits at every position
are compared with the same sequence fed alone, one id per call, through the same graph: top-1
agreement (all positions, and those where the alone run's top id leads by >= 0.05 logits, as in
bench/kv_fidelity.py), the largest |logit difference| and how many rows are bit-identical.

    python3 bench/rows_agreement.py MODEL_DIR [--decoders KEY ...] [--kv fp16|int8] [--rows 8]
        [--positions 512] [--points points.npy] [--threads 2] [--json OUT.json]

KEY: a model.json files key (decoder, decoder_int8, decoder_int4); each runs its contract v4
variant of the chosen cache (files.kv_fp16 / files.kv_int8).
"""

from __future__ import annotations

import argparse
import json
import sys
import time
from pathlib import Path

import numpy as np

from kv_fidelity import SHARED, cloud, compare, read_tokens, report, variant_file

from silk_export.onnx.decode import session  # noqa: E402  (kv_fidelity puts export/ on the path)

NUMPY = {"tensor(float)": np.float32, "tensor(float16)": np.float16, "tensor(int8)": np.int8}


def step_logits(sess, cross_kv: np.ndarray, seqs: list[list[int]]) -> np.ndarray:
    """Logits [R, L, V] of the R equal-length sequences fed together, one id per row per call."""
    types = {i.name: i.type for i in sess.get_inputs()}
    if "new_positions" not in types:
        raise SystemExit("rows_agreement: the graph is not decoder contract v4 (no new_positions input)")
    n_layers, _, h, _, d = cross_kv.shape
    cache = NUMPY[types["past_key_0"]]
    row = d + 4 if cache == np.int8 else d
    R, L = len(seqs), len(seqs[0])
    feeds = {}
    for l in range(n_layers):
        for k, name in enumerate(("cross_key", "cross_value")):
            feeds[f"{name}_{l}"] = np.ascontiguousarray(cross_kv[l, k][None], NUMPY[types[f"{name}_{l}"]])
    past = [np.zeros((R, h, 0, row), cache) for _ in range(2 * n_layers)]
    ids = np.asarray(seqs, np.int64)
    out = None
    for p in range(L):
        feeds.update(
            input_ids=ids[:, p : p + 1],
            positions=np.full((R, 1), p, np.int64),
            seqlens_k=np.full(R, p, np.int32),
            total_sequence_length=np.array(p + 1, np.int32),
            new_positions=np.ones(R, np.int32),
            cross_source=np.zeros(R, np.int32),
        )
        for l in range(n_layers):
            feeds[f"past_key_{l}"], feeds[f"past_value_{l}"] = past[2 * l], past[2 * l + 1]
        res = sess.run(None, feeds)
        if out is None:
            out = np.empty((R, L, res[0].shape[-1]), np.float32)
        out[:, p] = res[0][:, 0]
        past = res[1:]
    return out


def measure(model: Path, key: str, kv: str, seqs: dict[str, list[int]], points: Path, threads: int) -> dict:
    meta = json.loads((model / "model.json").read_text())
    files, dims = meta["files"], meta["dims"]
    cross = session(model / files.get("encoder", "encoder.onnx"), threads).run(
        None, {"points": cloud(points, dims["n_points"])}
    )[0]
    file = variant_file(model, files, key, kv)
    sess = session(model / file, threads)
    t0 = time.time()
    together = step_logits(sess, cross, list(seqs.values()))
    agree, decided, worst, identical = [], [], 0.0, 0
    for r, (name, seq) in enumerate(seqs.items()):
        alone = step_logits(sess, cross, [seq])[0]
        a, _, dec = compare(alone, together[r])
        agree.append(a)
        decided.append(dec)
        diff = float(np.abs(alone - together[r]).max())
        worst = max(worst, diff)
        identical += int(np.array_equal(alone, together[r]))
        print(
            f"  {key} {kv} {name}: top-1 {a.mean():.4f} (decided {a[dec].mean():.4f} of {dec.sum()}), "
            f"max |d| {diff:.3g}",
            flush=True,
        )
    a, dec = np.concatenate(agree), np.concatenate(decided)
    return {
        "file": file,
        "rows": len(seqs),
        "positions": int(a.size),
        "top1_agreement": round(float(a.mean()), 5),
        "decided_positions": int(dec.sum()),
        "top1_agreement_decided": round(float(a[dec].mean()), 5) if dec.any() else None,
        "max_abs_logit_difference": float(f"{worst:.3g}"),
        "bit_identical_rows": identical,
        "seconds": round(time.time() - t0, 1),
    }


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("model", type=Path)
    ap.add_argument("--decoders", nargs="+", default=["decoder", "decoder_int8"])
    ap.add_argument("--kv", default="fp16", choices=["fp16", "int8"])
    ap.add_argument("--rows", type=int, default=8)
    ap.add_argument("--positions", type=int, default=512, help="ids per sequence after BOS")
    ap.add_argument("--points", type=Path, default=SHARED / "official-fixture" / "points.npy")
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--json", type=Path)
    a = ap.parse_args()
    if not 1 <= a.rows <= 64 or not 1 <= a.positions <= 8192:
        raise SystemExit("rows_agreement: --rows must be 1-64 and --positions 1-8192")
    meta = json.loads((a.model / "model.json").read_text())
    bos = meta["vocab"]["bos_id"]
    dev = SHARED / "spec" / "golden-dev"
    long_enough = []
    for p in sorted(dev.glob("*.tokens.txt")):
        ids = read_tokens(p)
        if len(ids) >= a.positions:
            long_enough.append((p.name.split(".")[0], [bos] + ids[: a.positions]))
        if len(long_enough) == a.rows:
            break
    if len(long_enough) < a.rows:
        raise SystemExit(f"rows_agreement: only {len(long_enough)} golden-dev sequences have {a.positions} ids")
    seqs = dict(long_enough)
    result = {"model": str(a.model), "kv": a.kv, "decoders": {}}
    for key in a.decoders:
        result["decoders"][key] = measure(a.model, key, a.kv, seqs, a.points, a.threads)
    report(result, a.json)
    return 0


if __name__ == "__main__":
    sys.exit(main())
