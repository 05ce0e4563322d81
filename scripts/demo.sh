#!/usr/bin/env bash
# The main job on bundled data: builds Silk, tokenizes the bundled sample mesh and prints its
# statistics, then checks that decoding gives back every representable face.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh
mkdir -p out
./build/apps/silktok encode samples/torus_knot.obj -o out/torus_knot.tokens.txt
./build/apps/silktok stats samples/torus_knot.obj
./build/apps/silktok roundtrip samples/torus_knot.obj
echo "tokens written to out/torus_knot.tokens.txt"
