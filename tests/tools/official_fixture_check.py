#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""The released Mesh Silksong architecture end to end through libsilk (ctest official_fixture_greedy):
imports ../shared/official-fixture/model.safetensors with `python3 -m silk_export import-official`
(at test time, nothing committed), writes the fixture's conditioning points (points.npy, float32
[4096, 6]) as a point-cloud PLY, and requires

  generate_unconstrained points.ply --model IMPORTED --raw-points --temperature 0 --max-tokens 100
          --tokens out.txt

(tests/tools/generate_unconstrained.cpp: the official loop has no grammar mask, so neither may this run)

to print exactly greedy.txt, the official implementation's 100 greedy ids (README of the fixture),
once with the fp32 decoder and once with the importer's default decoder.
Usage: official_fixture_check.py GENERATE_UNCONSTRAINED REPO SHARED_DIR. Exit 77 (ctest SKIP) when the fixture or
the Python packages the importer needs (numpy, torch, onnx, onnxruntime) are missing."""

import importlib.util
import os
import pathlib
import subprocess
import sys
import tempfile

from check_report import finish


def skip(why):
    print(f"official_fixture_check: SKIPPED: {why}")
    return 77


def write_cloud_ply(path, points):
    import numpy as np

    head = "ply\nformat binary_little_endian 1.0\nelement vertex %d\n" % len(points)
    head += "".join(f"property float {a}\n" for a in ("x", "y", "z", "nx", "ny", "nz")) + "end_header\n"
    path.write_bytes(head.encode() + np.ascontiguousarray(points, dtype="<f4").tobytes())


def main():
    if len(sys.argv) != 4:
        print(__doc__)
        return 2
    tool, repo, shared = (pathlib.Path(a).resolve() for a in sys.argv[1:])
    fixture = shared / "official-fixture"
    if not (fixture / "model.safetensors").exists():
        return skip(f"no official fixture in {fixture}")
    missing = [m for m in ("numpy", "torch", "onnx", "onnxruntime") if importlib.util.find_spec(m) is None]
    if missing:
        return skip(f"Python packages missing for silk-export import-official: {', '.join(missing)}")
    import numpy as np

    want = (fixture / "greedy.txt").read_text().split()
    failures = []
    with tempfile.TemporaryDirectory() as tmp:
        tmp = pathlib.Path(tmp)
        env = dict(os.environ, PYTHONPATH=str(repo / "export") + os.pathsep + os.environ.get("PYTHONPATH", ""))
        p = subprocess.run(
            [
                sys.executable,
                "-m",
                "silk_export",
                "import-official",
                str(fixture / "model.safetensors"),
                "-o",
                str(tmp / "model"),
                "--config",
                str(fixture / "config.json"),
                "--no-progress",
            ],
            capture_output=True,
            text=True,
            env=env,
            timeout=600,
        )
        if p.returncode != 0:
            print(p.stdout + p.stderr)
            print("FAIL: import-official failed")
            return 1
        print(p.stdout.strip().splitlines()[-1] if p.stdout.strip() else "imported")
        write_cloud_ply(tmp / "points.ply", np.load(fixture / "points.npy"))
        for label, extra in (("fp32", ["--decoder", "fp32"]), ("default decoder", [])):
            out = tmp / "out.txt"
            cmd = [
                str(tool),
                str(tmp / "points.ply"),
                "--model",
                str(tmp / "model"),
                "--raw-points",
                "--temperature",
                "0",
                "--max-tokens",
                "100",
                "--tokens",
                str(out),
                *extra,
            ]
            r = subprocess.run(cmd, capture_output=True, text=True, timeout=300)
            got = out.read_text().split() if r.returncode == 0 else []
            same = sum(a == b for a, b in zip(got, want))
            print(
                f"{label}: {len(got)} ids, {same} of {len(want)} equal to greedy.txt"
                + ("" if r.returncode == 0 else f" (generate_unconstrained exit {r.returncode}: {r.stderr.strip()})")
            )
            if got != want:
                first = next((i for i, (a, b) in enumerate(zip(got, want)) if a != b), min(len(got), len(want)))
                failures.append(f"{label}: differs from greedy.txt at line {first + 1}")
    return finish("official fixture greedy", failures)


if __name__ == "__main__":
    sys.exit(main())
