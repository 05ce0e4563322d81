#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Exports random-weight models of the tiny / small / paper shapes (export/silk_export/models/configs.py)
and of the released official network ("official": arch official at the release size, 601 M
parameters) for bench/generation_bench.cpp, at bench time (never committed: paper is ~2 GB in
fp32, official ~2.4 GB). Each goes to OUT/<config>/ with model.json, encoder.onnx, decoder.onnx,
decoder.int8.onnx; "official" also gets decoder.int4.onnx and the importer's fidelity figures
(model.json "import.fidelity": top-1 agreement and KL of each variant vs fp32). Every folder
gets, as `silk-export export` / import-official write them, the fp16- and int8-cache variants
of every decoder in decoder contract v4 (R rows per call) and model_version 4 (time_to_mesh --rows).

    python3 bench/export_bench_models.py --out /tmp/silk-bench-models [--configs tiny small paper official]
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

from silk_export.json_io import dumps, write_json  # noqa: E402
from silk_export.models.configs import get_config  # noqa: E402
from silk_export.models.silk_model import SilkModel  # noqa: E402
from silk_export.onnx.export import export_graphs, export_model, sidecar, transpose_linears  # noqa: E402
from silk_export.onnx.rows import ROWS_CONTRACT  # noqa: E402

RANDOM = {"steps": 0, "data": "random weights (benchmark)"}


def export_official(out: Path, seed: int, int4_block: int, int4_accuracy: int) -> int:
    """Release-size official network, random weights; all three decoders + fidelity figures + the
    contract v4 cache variants (write_variants), so model.json says model_version 4 as import-official's."""
    from silk_export.official.checkpoint import RELEASE_SIZES, official_config
    from silk_export.import_official import write_variants
    from silk_export.official.model import OfficialModel

    model = OfficialModel(official_config(RELEASE_SIZES, {})).init_random(seed=seed)
    cfg, params = model.cfg, model.num_parameters()
    files = export_graphs(transpose_linears(model), out)
    del model
    figures = write_variants(out, files, cfg, "auto", int4_block, int4_accuracy)
    meta = sidecar(
        cfg,
        {**RANDOM, "seed": seed},
        files,
        {"import": {"fidelity": figures, "int4": {"block_size": int4_block, "accuracy_level": int4_accuracy}}},
        ROWS_CONTRACT,
    )
    write_json(out / "model.json", meta)
    return params


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--out", required=True)
    ap.add_argument("--configs", nargs="+", default=["tiny", "small", "paper"])
    ap.add_argument("--no-int8", action="store_true")
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--int4-block-size", type=int, default=32)
    ap.add_argument("--int4-accuracy-level", type=int, default=4)
    a = ap.parse_args()
    torch.set_num_threads(2)
    for name in a.configs:
        out = Path(a.out) / name
        # export_model and export_official both write contract v4 variants with model_version 4
        current = (out / "model.json").exists() and json.loads((out / "model.json").read_text()).get(
            "model_version"
        ) == ROWS_CONTRACT
        if current and (a.no_int8 or (out / "decoder.int8.onnx").exists()):
            print(f"{name}: already in {out}")
            continue
        t0 = time.time()
        torch.manual_seed(a.seed)
        if name == "official":
            params = export_official(out, a.seed, a.int4_block_size, a.int4_accuracy_level)
        else:
            model = SilkModel(get_config(name))
            params = model.num_parameters()
            export_model(model, out, {**RANDOM, "seed": a.seed}, int8=not a.no_int8)
            del model
        sizes = {f.name: round(f.stat().st_size / 2**20, 1) for f in sorted(out.iterdir())}
        print(dumps({"config": name, "params": params, "MiB": sizes, "seconds": round(time.time() - t0, 1)}, "null"))
    return 0


if __name__ == "__main__":
    sys.exit(main())
