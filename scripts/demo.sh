#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# The main job on bundled data: builds Silk, generates a mesh from the bundled sample input with
# the bundled default model (silkgen, CPU, no Python), then tokenizes the sample and prints its
# statistics and round-trip check (silktok).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh
mkdir -p out
if [ -x ./build/apps/silkgen ]; then
  ./build/apps/silkgen samples/torus_knot.obj -o out/torus_knot.glb --stats out/torus_knot.stats.json
  echo "generated mesh: out/torus_knot.glb (statistics in out/torus_knot.stats.json)"
  bash scripts/render_pictures.sh demo out/torus_knot.png  # the input beside the output (needs blender)
else
  echo "silkgen was not built (onnxruntime missing: run scripts/setup.sh)" >&2
fi
./build/apps/silktok encode samples/torus_knot.obj -o out/torus_knot.tokens.txt
./build/apps/silktok stats samples/torus_knot.obj
./build/apps/silktok roundtrip samples/torus_knot.obj
echo "tokens written to out/torus_knot.tokens.txt"
