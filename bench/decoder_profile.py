#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""decoder_profile: where one decoder call's time goes at a given depth, per operator type, for
each KV variant of a model folder (fp32 cache = the decoder itself; fp16 / int8 = files.kv_fp16 /
files.kv_int8; PRECISION@FOLDER = that variant of another folder, e.g. one rewritten with
`silk-export kv16 --attention ort`). The cache is bound in place, as libsilk runs it (present_*
over past_*'s own buffer, capacity = depth + calls), filled with random rows; onnxruntime's
profiler gives each node's kernel time, summed per operator type and averaged over the calls.
Beside the table: the wall time per call without the profiler, and the bytes one call reads.

    python3 bench/decoder_profile.py MODEL_DIR [--decoder decoder_int4] [--kv fp32 fp16 int8]
        [--depths 0 4096] [--calls 12] [--threads 2] [--top 10]

libsilk_ops is registered with onnxruntime for the ai.silk ops (beside $SILK_LIBRARY or the build tree's
libsilk; $SILK_OPS_LIBRARY).
"""

from __future__ import annotations

import argparse
import collections
import json
import os
import sys
import tempfile
import time
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPO / "export"))

import numpy as np  # noqa: E402

from silk_export.onnx.decode import silk_ops_library  # noqa: E402

NUMPY = {"tensor(float)": np.float32, "tensor(float16)": np.float16, "tensor(int8)": np.int8}


def decoder_file(model: Path, key: str, kv: str) -> Path:
    """The graph of decoder `key` with cache `kv` ("fp32", "fp16", "int8", or any of them @FOLDER)."""
    kv, _, other = kv.partition("@")
    folder = Path(other) if other else model
    files = json.loads((folder / "model.json").read_text())["files"]
    name = files[key] if kv == "fp32" else files.get(f"kv_{kv}", {}).get(key)
    if not name:
        raise SystemExit(f"{folder}: no {kv} cache variant of {key}")
    return folder / name


def make_session(path: Path, threads: int, profile: bool):
    import onnxruntime as ort

    so = ort.SessionOptions()
    so.intra_op_num_threads = threads
    so.log_severity_level = 3
    so.register_custom_ops_library(silk_ops_library())
    if profile:
        so.enable_profiling = True
        so.profile_file_prefix = os.path.join(tempfile.gettempdir(), "silk_decoder_profile")
    return ort.InferenceSession(str(path), so, providers=["CPUExecutionProvider"])


def bind(s, depth: int, calls: int, n_latents: int):
    """An IOBinding with random cache rows (in place: present_* = past_*), cross K/V and room for
    `calls` positions after `depth`; returns it with the arrays it points into."""
    import onnxruntime as ort

    rng, b, keep = np.random.default_rng(0), s.io_binding(), []
    for i in s.get_inputs():
        if not (i.name.startswith("past_") or i.name.startswith("cross_")):
            continue
        shape = [
            d if isinstance(d, int) else (depth + calls if i.name.startswith("past_") else n_latents) for d in i.shape
        ]
        dt = NUMPY[i.type]
        a = rng.integers(-100, 100, shape).astype(dt) if dt == np.int8 else (rng.normal(size=shape) * 0.3).astype(dt)
        if dt == np.int8:  # the last four bytes of each row: a float32 scale
            a[..., -4:] = np.full(shape[:-1], 0.01, np.float32)[..., None].view(np.int8)
        v = ort.OrtValue.ortvalue_from_numpy(a)
        keep += [a, v]
        b.bind_ortvalue_input(i.name, v)
        if i.name.startswith("past_"):
            b.bind_ortvalue_output(i.name.replace("past_", "present_"), v)
    b.bind_output("logits")
    return b, keep


def run_calls(s, b, keep, depth: int, calls: int) -> list[float]:
    times = []
    for k in range(calls):
        p = depth + k
        for name, val in (
            ("input_ids", np.array([[5]], np.int64)),
            ("positions", np.array([[p]], np.int64)),
            ("seqlens_k", np.array([p], np.int32)),
            ("total_sequence_length", np.array(p + 1, np.int32)),
        ):
            keep.append(val)
            b.bind_cpu_input(name, val)
        t = time.perf_counter()
        s.run_with_iobinding(b)
        times.append(time.perf_counter() - t)
    return times


def op_times(profile_file: str, calls: int) -> dict[str, float]:
    """ms per call per operator type from onnxruntime's profile (the warm-up call excluded)."""
    events = json.loads(Path(profile_file).read_text())
    os.remove(profile_file)
    runs = [e for e in events if e.get("name") == "model_run"]
    start = runs[1]["ts"] if len(runs) > 1 else 0
    out = collections.Counter()
    for e in events:
        if e.get("cat") == "Node" and e["name"].endswith("_kernel_time") and e["ts"] >= start:
            out[e["args"].get("op_name", "?")] += e["dur"] / 1e3 / calls
    return out


def profile(path: Path, depth: int, calls: int, threads: int, n_latents: int) -> tuple[float, dict]:
    s = make_session(path, threads, profile=False)
    b, keep = bind(s, depth, calls + 1, n_latents)
    wall = sorted(run_calls(s, b, keep, depth, calls + 1)[1:])[calls // 2] * 1e3
    s = make_session(path, threads, profile=True)
    b, keep = bind(s, depth, calls + 1, n_latents)
    run_calls(s, b, keep, depth, calls + 1)
    return wall, op_times(s.end_profiling(), calls)


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("model", type=Path)
    ap.add_argument("--decoder", default="decoder_int4", help="model.json files key")
    ap.add_argument("--kv", nargs="+", default=["fp32", "fp16", "int8"])
    ap.add_argument("--depths", nargs="+", type=int, default=[0, 4096])
    ap.add_argument("--calls", type=int, default=12)
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--top", type=int, default=10)
    a = ap.parse_args()
    meta = json.loads((a.model / "model.json").read_text())
    d = meta["dims"]
    row_bytes = {"fp32": 4 * d["head_dim"], "fp16": 2 * d["head_dim"], "int8": d["head_dim"] + 4}
    print(
        f"decoder_profile: {a.model} {a.decoder}, {a.threads} threads, {a.calls} calls per depth "
        f"(median wall ms per call without the profiler; kernel ms per call by operator type)"
    )
    for kv in a.kv:
        path = decoder_file(a.model, a.decoder, kv)
        for depth in a.depths:
            wall, ops = profile(path, depth, a.calls, a.threads, d["n_latents"])
            cache_mb = depth * d["n_layers"] * 2 * d["n_heads"] * row_bytes[kv.split("@")[0]] / 1e6
            total = sum(ops.values())
            top = ", ".join(f"{op} {ms:.1f}" for op, ms in ops.most_common(a.top))
            print(
                f"{kv:>8} depth {depth:5d}: wall {wall:6.1f} ms | kernels {total:6.1f} ms (cache read "
                f"{cache_mb:5.0f} MB): {top}",
                flush=True,
            )
    return 0


if __name__ == "__main__":
    sys.exit(main())
