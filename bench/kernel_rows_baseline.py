# SPDX-License-Identifier: MIT
"""Builds bench/kernel_rows against an earlier revision's ai.silk kernels (its engine/ from git,
compiled with exactly the flags build/compile_commands.json gives this tree's kernels, with
-DSILK_KERNEL_ROWS_ONE_ROW: R = 1 only), then runs that baseline and this build's kernel_rows in
turns, so "a batch of one costs what one row cost before" is measured in one run on one machine.

    python3 bench/kernel_rows_baseline.py REV [--build build] [--turns 2] [-- kernel_rows args]
"""

from __future__ import annotations

import argparse
import json
import shlex
import subprocess
import sys
import tarfile
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
KERNELS = ["cpu/float16.cpp", "attention/attention_rows.cpp", "attention/cache_row.cpp",
           "attention/cached_attention.cpp", "attention/cross_attention.cpp", "quant/int4_matmul.cpp",
           "quant/half_matmul.cpp", "ort/ort_op_glue.cpp"]  # fmt: skip


def _command(build: Path, source: Path) -> list[str]:
    for e in json.loads((build / "compile_commands.json").read_text()):
        if Path(e["file"]).resolve() == source.resolve():
            return e["arguments"] if "arguments" in e else shlex.split(e["command"])
    sys.exit(f"kernel_rows_baseline: {source} is not in {build}/compile_commands.json (build kernel_rows first)")


def _compile(build: Path, source: Path, old_engine: Path, out: Path, extra: list[str]) -> None:
    args = _command(build, ROOT / "engine" / "kernels" / "quant" / "int4_matmul.cpp")
    if source.name == "kernel_rows.cpp":
        args = _command(build, source)
    keep = [a for i, a in enumerate(args) if a not in ("-o", "-c") and (i == 0 or args[i - 1] not in ("-o", "-c"))]
    keep = [keep[0], f"-I{old_engine}"] + keep[1:] + extra
    subprocess.run([*keep, "-c", str(source), "-o", str(out)], check=True)


def main() -> int:
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("rev", help="the revision whose kernels are the baseline (e.g. the merge base)")
    p.add_argument("--build", default="build", help="this tree's build folder (with kernel_rows built)")
    p.add_argument("--turns", type=int, default=2, help="baseline/current pairs, run in turns")
    argv = sys.argv[1:]
    split = argv.index("--") if "--" in argv else len(argv)
    a = p.parse_args(argv[:split])
    a.bench_args = argv[split + 1 :]
    build = (ROOT / a.build).resolve()
    current = build / "bench" / "kernel_rows"
    if not current.exists():
        sys.exit(f"kernel_rows_baseline: {current} is missing: cmake --build {a.build} --target kernel_rows")
    with tempfile.TemporaryDirectory() as tmp:
        tmp_path = Path(tmp)
        archive = subprocess.run(["git", "-C", str(ROOT), "archive", a.rev, "engine"], check=True, capture_output=True)
        (tmp_path / "engine.tar").write_bytes(archive.stdout)
        with tarfile.open(tmp_path / "engine.tar") as t:
            t.extractall(tmp_path, filter="data")
        old = tmp_path / "engine"
        objects = []
        for i, rel in enumerate(KERNELS):
            if (old / "kernels" / rel).exists():
                objects.append(tmp_path / f"k{i}.o")
                _compile(build, old / "kernels" / rel, old, objects[-1], [])
        objects.append(tmp_path / "kernel_rows.o")
        _compile(build, ROOT / "bench" / "kernel_rows.cpp", old, objects[-1], ["-DSILK_KERNEL_ROWS_ONE_ROW"])
        baseline = tmp_path / "kernel_rows_baseline"
        subprocess.run(["c++", "-pthread", *map(str, objects), "-o", str(baseline)], check=True)
        for turn in range(a.turns):
            for label, exe in ((f"baseline ({a.rev})", baseline), ("this tree", current)):
                print(f"--- turn {turn + 1}: {label}", flush=True)
                subprocess.run([str(exe), *a.bench_args], check=True)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
