#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Generates from every dev-corpus mesh with the bundled model, grammar on (silkgen) vs off
# (tests/tools/generate_unconstrained, a test build's; same weights, seed 0, 1 thread, 512-token
# cap), summarises the reports' verdicts and runs `silk-export eval` (CD/HD/NC/|NC| + structure)
# on the grammar outputs.
# Usage: [BUILD_DIR=build] scripts/eval_dev_generation.sh [OUT_DIR=out/dev_generation] [MAX_TOKENS=512]
set -euo pipefail
cd "$(dirname "$0")/.."
out="${1:-out/dev_generation}"; max_tokens="${2:-512}"
source scripts/shared_dir.sh
shared=$(silk_shared_dir) || exit 2
silkgen="${BUILD_DIR:-build}/apps/silkgen"
unconstrained="${BUILD_DIR:-build}/tests/generate_unconstrained"
[ -x "$silkgen" ] || { echo "$silkgen not built (run scripts/build.sh)" >&2; exit 1; }
[ -x "$unconstrained" ] ||
  { echo "$unconstrained not built (run scripts/build.sh -DSILK_BUILD_TESTS=ON)" >&2; exit 1; }
for mode in grammar unconstrained; do
  mkdir -p "$out/$mode"
  tool=("$silkgen"); [ "$mode" = unconstrained ] && tool=("$unconstrained")
  for f in "$shared"/corpus/dev/*.obj; do
    n=$(basename "$f" .obj)
    "${tool[@]}" "$f" -o "$out/$mode/$n.obj" --seed 0 --threads 1 --max-tokens "$max_tokens" \
      --stats "$out/$mode/$n.json" >/dev/null 2>"$out/$mode/$n.err" || true
  done
done
python3 - "$out" <<'PY'
import glob, json, sys
out = sys.argv[1]
for mode in ("grammar", "unconstrained"):
    runs = [json.load(open(f)) for f in sorted(glob.glob(f"{out}/{mode}/*.json"))]
    with_faces = [r for r in runs if r.get("faces", 0) > 0]
    ok = [r for r in with_faces if r["verdicts"]["edge_manifold"] and r["verdicts"]["consistently_oriented"]]
    print(f"{mode}: {len(runs)} runs, {len(with_faces)} with faces, {len(ok)} edge-manifold and consistently "
          f"oriented, {sum(r['verdicts']['watertight'] for r in runs)} watertight, "
          f"{sum(r.get('faces', 0) for r in runs)} faces, {sum(r['seconds']['total'] for r in runs):.1f} s")
PY
mkdir -p "$out/ref"
for f in "$out"/grammar/*.obj; do ln -sf "$(cd "$shared/corpus/dev" && pwd)/$(basename "$f")" "$out/ref/$(basename "$f")"; done
silk-export eval "$out/grammar" "$out/ref" --out "$out/eval.json" >/dev/null
python3 -c "import json,sys; print(json.dumps(json.load(open(sys.argv[1]))['summary'], allow_nan=False))" "$out/eval.json"
