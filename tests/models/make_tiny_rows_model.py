# SPDX-License-Identifier: MIT
"""Makes tests/models/tiny-rows/: the tiny test model (tests/models/tiny, same weights) as a
model_version 4 folder whose INT4 decoder's fp16- and int8-cache variants are in decoder contract
v4 (R rows per call, docs/model_contract.md), so the runtime's rows tests run libsilk's ai.silk
kernels, with which a row's ids are exactly its ids alone; and an INT8 decoder (onnxruntime's
dynamic quantization: one activation scale per call, so its rows are not each their own) with the
same cache variants, which best of N must run one row at a time.

    python3 tests/models/make_tiny_rows_model.py [--out tests/models/tiny-rows]
"""

import argparse
import json
import shutil
import sys
from pathlib import Path

REPO = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(REPO / "export"))

from silk_export.onnx.export import quantize_decoder, quantize_decoder_int4  # noqa: E402
from silk_export.onnx.kv_precision import add_kv_to_folder  # noqa: E402


def make(src: Path, out: Path) -> None:
    src, out = src.resolve(), out.resolve()
    if out == src or out in src.parents or src in out.parents:
        raise SystemExit(f"make_tiny_rows_model: --out {out} overlaps --src {src}; it is removed and rewritten")
    if out.exists():
        shutil.rmtree(out)
    out.mkdir(parents=True)
    for name in ("encoder.onnx", "decoder.onnx"):
        shutil.copy(src / name, out / name)
    quantize_decoder_int4(out / "decoder.onnx", out / "decoder.int4.onnx")
    quantize_decoder(out / "decoder.onnx", out / "decoder.int8.onnx")
    meta = json.loads((src / "model.json").read_text())
    meta["model_version"] = 4
    meta["arch"] = "silk"
    meta["config"] = "test-tiny-rows"
    meta["files"] = {
        "encoder": "encoder.onnx",
        "decoder": "decoder.onnx",
        "decoder_int8": "decoder.int8.onnx",
        "decoder_int4": "decoder.int4.onnx",
        "default_decoder": "decoder_int4",
    }
    (out / "model.json").write_text(json.dumps(meta, indent=2) + "\n")
    for precision in ("fp16", "int8"):
        add_kv_to_folder(out, precision, default="fp16" if precision == "fp16" else None, rows=True)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--src", default=str(REPO / "tests" / "models" / "tiny"))
    ap.add_argument("--out", default=str(REPO / "tests" / "models" / "tiny-rows"))
    a = ap.parse_args()
    make(Path(a.src), Path(a.out))


if __name__ == "__main__":
    main()
