#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Meshes per hour of `silkgen --batch` (docs/batch.md) over a fixed subset of the dev corpus
(every STRIDE-th file of the sorted list), each figure beside the baseline measured in the same
run: one `silkgen FILE` process per mesh (the model loaded each time), 2 threads.

  1 process x 2 threads     silkgen --batch LIST --threads 2
  2 processes x 1 thread    silkgen --batch LIST --shard i/2 --threads 1, both at once
  best of N                 the 1 x 2 run with --candidates N against --candidates 1
  best of N as rows         the same with --rows 1 (one candidate after another) and --rows R
                            (up to R candidates in one decoder call per step; the same outputs,
                            byte for byte: checked here)
  several meshes as rows    with --parallel P1,P2,...: the 1 x 2 run, best of 1, with --parallel P
                            (up to P meshes in one decoder call per step; a decoder contract v4
                            folder), each beside --parallel 1 of the same run (which is always
                            measured) and its outputs byte-identical to it (checked here)

Usage: python3 bench/batch_throughput.py [--silkgen build/apps/silkgen] [--model DIR]
       [--corpus ../shared/corpus/dev] [--stride 20] [--candidates 8] [--rows 8] [--max-tokens 0]
       [--parallel 1,2,4,8]
"""

import argparse
import pathlib
import subprocess
import sys
import tempfile
import time

ROOT = pathlib.Path(__file__).resolve().parents[1]


def timed(cmds):
    """Runs the commands at once; wall seconds until the last ends (each must exit 0)."""
    t0 = time.perf_counter()
    procs = [subprocess.Popen([str(c) for c in cmd], stdout=subprocess.DEVNULL, stderr=subprocess.PIPE) for cmd in cmds]
    for p, cmd in zip(procs, cmds):
        err = p.communicate()[1]
        if p.returncode != 0:
            sys.exit(f"failed ({p.returncode}): {' '.join(map(str, cmd))}\n{err.decode()[-2000:]}")
    return time.perf_counter() - t0


def same_outputs(one, many, option="--rows"):
    """The rows run's meshes are the one-after-another run's, byte for byte (exits otherwise)."""
    a, b = sorted(p.name for p in one.glob("*.glb")), sorted(p.name for p in many.glob("*.glb"))
    differ = [n for n in a if (one / n).read_bytes() != (many / n).read_bytes()]
    if a != b or not a or differ:
        sys.exit(f"{option} changed the outputs: {one} {len(a)} files, {many} {len(b)} files, differing {differ[:5]}")
    print(f"{option} ({many.name}): {len(a)} outputs byte-identical to {option} 1")


def parallel_rows(a, batch, tmp):
    """(name, seconds) of best of 1 at each --parallel P, --parallel 1 first; outputs checked."""
    values = sorted({1, *(int(p) for p in a.parallel.split(","))})
    rows = []
    for p in values:
        name = f"--batch 1 process x 2 threads, best of 1, --parallel {p}"
        rows.append(
            (name, timed([[a.silkgen, *batch(f"b12_p{p}", "--threads", 2, "--candidates", 1, "--parallel", p)]]))
        )
        if p > 1:
            same_outputs(tmp / "b12_p1", tmp / f"b12_p{p}", "--parallel")
    return rows


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--silkgen", default=ROOT / "build/apps/silkgen", type=pathlib.Path)
    ap.add_argument("--model", default=ROOT / "models/default", type=pathlib.Path)
    ap.add_argument("--corpus", default=ROOT.parent / "shared/corpus/dev", type=pathlib.Path)
    ap.add_argument("--stride", type=int, default=20, help="every STRIDE-th file of the sorted corpus")
    ap.add_argument("--candidates", type=int, default=8, help="N of the best-of-N row")
    ap.add_argument("--rows", type=int, default=8, help="R of the best-of-N-as-rows row")
    ap.add_argument("--max-tokens", type=int, default=0, help="id cap per mesh (0 = the model's)")
    ap.add_argument("--parallel", default="", help="comma-separated P of the several-meshes-as-rows rows (1,2,4,8)")
    a = ap.parse_args()
    files = sorted(a.corpus.glob("*.obj"))[:: a.stride]
    common = ["--model", a.model, "--seed", "0", "--max-tokens", a.max_tokens, "-q"]
    with tempfile.TemporaryDirectory() as tmp:
        tmp = pathlib.Path(tmp)
        lst = tmp / "list.txt"
        lst.write_text("".join(f"{f}\n" for f in files))

        def batch(name, *extra):
            return ["--batch", lst, "-o", tmp / name, *common, *extra]

        rows = []
        timed([[a.silkgen, files[0], "-o", tmp / "warm.glb", *common, "--threads", 2, "--candidates", 1]])  # page cache
        base = sum(
            timed([[a.silkgen, f, "-o", tmp / f"single_{f.stem}.glb", *common, "--threads", 2, "--candidates", 1]])
            for f in files
        )
        rows.append(("separate processes, 2 threads, best of 1 (baseline)", base))
        rows.append(
            (
                "--batch 1 process x 2 threads, best of 1",
                timed([[a.silkgen, *batch("b12", "--threads", 2, "--candidates", 1)]]),
            )
        )
        rows.append(
            (
                "--batch 2 processes x 1 thread, best of 1",
                timed(
                    [
                        [a.silkgen, *batch("b21", "--threads", 1, "--candidates", 1, "--shard", f"{i}/2")]
                        for i in range(2)
                    ]
                ),
            )
        )
        for r in (1, a.rows):
            rows.append(
                (
                    f"--batch 1 process x 2 threads, best of {a.candidates}, --rows {r}",
                    timed(
                        [[a.silkgen, *batch(f"b12n_r{r}", "--threads", 2, "--candidates", a.candidates, "--rows", r)]]
                    ),
                )
            )
        same_outputs(tmp / "b12n_r1", tmp / f"b12n_r{a.rows}")
        parallel = parallel_rows(a, batch, tmp) if a.parallel else []
        rows += parallel
    print(f"{len(files)} meshes (every {a.stride}th of {a.corpus}), model {a.model}, max-tokens {a.max_tokens}")
    print(f"{'configuration':58s} {'wall s':>8s} {'meshes/h':>9s} {'vs baseline':>11s}")
    for name, s in rows:
        print(f"{name:58s} {s:8.1f} {len(files) * 3600 / s:9.0f} {base / s:10.2f}x")
    for name, s in parallel[1:]:
        print(f"{name}: {parallel[0][1] / s:.2f}x the meshes per hour of --parallel 1 (same run)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
