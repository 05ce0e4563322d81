#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Cost of face guidance per sampled id (docs/runtime.md "Face guidance"): silkgen runs on the same
inputs and seeds with --face-guidance off / hard / soft (one candidate each, so a run is one
generation), read back from --stats: microseconds of the token loop per sampled id, of that the
face-guidance stage's share, judged steps and fallbacks per mesh. The off row is the baseline
measured in the same invocation.

    python3 bench/face_guidance_cost.py SILKGEN MODEL_DIR INPUT... [--tolerance 3] [--threads 1]
"""

import argparse
import json
import pathlib
import subprocess
import sys
import tempfile


def run(silkgen, model, src, mode, tolerance, threads, out):
    stats = out / f"{pathlib.Path(src).stem}.{mode}.json"
    cmd = [
        silkgen,
        src,
        "-o",
        out / f"{pathlib.Path(src).stem}.{mode}.obj",
        "--model",
        model,
        "--candidates",
        "1",
        "--threads",
        str(threads),
        "--face-guidance",
        mode,
        "--face-tolerance",
        str(tolerance),
        "--stats",
        stats,
        "-q",
    ]
    subprocess.run([str(c) for c in cmd], check=True)
    return json.loads(stats.read_text())


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("silkgen")
    ap.add_argument("model")
    ap.add_argument("inputs", nargs="+")
    ap.add_argument("--tolerance", type=float, default=3.0)
    ap.add_argument("--threads", type=int, default=1)
    a = ap.parse_args()
    print(
        "| face guidance | meshes | sampled ids/mesh | us per sampled id (loop) | of which face guidance | "
        "judged steps/mesh | fallbacks/mesh | faces/mesh |"
    )
    print("|---|---|---|---|---|---|---|---|")
    with tempfile.TemporaryDirectory() as tmp:
        out = pathlib.Path(tmp)
        for mode in ("off", "hard", "soft"):
            rows = [run(a.silkgen, a.model, s, mode, a.tolerance, a.threads, out) for s in a.inputs]
            sampled = sum(r["sampled_tokens"] for r in rows)
            loop = sum(
                r["seconds"]["total"]
                - r["seconds"]["load_input"]
                - r["seconds"]["encoder"]
                - r["seconds"]["build_mesh"]
                - r["seconds"]["scoring"]
                for r in rows
            )
            face = sum(r["face_guidance"]["seconds"] for r in rows)
            n = len(rows)
            print(
                f"| {mode} (tolerance {a.tolerance:g}) | {n} | {sampled / n:.0f} | {1e6 * loop / sampled:.1f} | "
                f"{1e6 * face / sampled:.1f} | {sum(r['face_guidance']['guided_tokens'] for r in rows) / n:.0f} | "
                f"{sum(r['face_guidance']['fallbacks'] for r in rows) / n:.1f} | {sum(r['faces'] for r in rows) / n:.0f} |"
            )
    return 0


if __name__ == "__main__":
    sys.exit(main())
