#!/usr/bin/env python3
"""Exports random-weight models of the tiny / small / paper shapes (export/silk_export/configs.py)
for bench/generation_bench.cpp, at bench time (never committed: paper is ~2 GB in fp32).
Each goes to OUT/<config>/ with model.json, encoder.onnx, decoder.onnx, decoder.int8.onnx.

    python3 bench/export_bench_models.py --out /tmp/silk-bench-models [--configs tiny small paper]
"""
from __future__ import annotations

import argparse
import json
import sys
import time
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPO / "export"))

import torch  # noqa: E402

from silk_export.configs import get_config  # noqa: E402
from silk_export.model import SilkModel  # noqa: E402
from silk_export.onnx_export import MODEL_VERSION, export_model  # noqa: E402


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--out", required=True)
    ap.add_argument("--configs", nargs="+", default=["tiny", "small", "paper"])
    ap.add_argument("--no-int8", action="store_true")
    ap.add_argument("--seed", type=int, default=0)
    a = ap.parse_args()
    torch.set_num_threads(2)
    for name in a.configs:
        out = Path(a.out) / name
        current = (out / "model.json").exists() and \
            json.loads((out / "model.json").read_text()).get("model_version") == MODEL_VERSION
        if current and (a.no_int8 or (out / "decoder.int8.onnx").exists()):
            print(f"{name}: already in {out}")
            continue
        t0 = time.time()
        torch.manual_seed(a.seed)
        model = SilkModel(get_config(name))
        export_model(model, out, {"steps": 0, "data": "random weights (benchmark)", "seed": a.seed},
                     int8=not a.no_int8)
        sizes = {f.name: round(f.stat().st_size / 2**20, 1) for f in sorted(out.iterdir())}
        print(json.dumps({"config": name, "params": model.num_parameters(), "MiB": sizes,
                          "seconds": round(time.time() - t0, 1)}))
        del model
    return 0


if __name__ == "__main__":
    sys.exit(main())
