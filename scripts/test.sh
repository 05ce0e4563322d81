#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Builds and runs every test: the normal build (unit, golden, dev-corpus, CLI and bad-input
# tests), then an ASan + UBSan build of the same tests (the slow dev-corpus suites excluded).
set -euo pipefail
cd "$(dirname "$0")/.."
JOBS=${JOBS:-$(nproc)}

# The shared material (spec/, corpus/) every stage reads (scripts/shared_dir.sh: $SILK_SHARED_DIR,
# else ../shared beside this checkout, else beside the checkout it was cloned from).
source scripts/shared_dir.sh
SILK_SHARED_DIR=$(silk_shared_dir) || exit 2
if [ ! -d "$SILK_SHARED_DIR/spec/golden" ] || [ ! -d "$SILK_SHARED_DIR/corpus/dev" ]; then
  echo "test: no shared material (spec/golden, corpus/dev) in $SILK_SHARED_DIR: set SILK_SHARED_DIR to the folder that holds it" >&2
  exit 2
fi
export SILK_SHARED_DIR
echo "test: shared material from $SILK_SHARED_DIR"

# Seconds per stage, printed when the script ends (passed or not): where a CI run's time went.
STAGE="build + ctest"
STAGE_START=$SECONDS
STAGE_TIMES=()
stage() {  # closes the running stage and opens the next under a header
  STAGE_TIMES+=("$STAGE: $((SECONDS - STAGE_START)) s")
  STAGE=$1
  STAGE_START=$SECONDS
  echo "=== $1 ==="
}
trap 'stage end >/dev/null; printf "test: %s\n" "${STAGE_TIMES[@]}" "total: $SECONDS s"' EXIT

bash scripts/build.sh -DSILK_BUILD_TESTS=ON -DSILK_SHARED_DIR="$SILK_SHARED_DIR"  # fails where GoogleTest/OpenMesh are missing (setup.sh --test)
(cd build && ctest --output-on-failure -j "$JOBS")

stage "export/ (pytest, through build/engine/libsilk.so)"
SILK_LIBRARY="$PWD/build/engine/libsilk.so" python3 -m pytest -q export/tests

# The pip wheel (scripts/build_wheel.sh: a Release build of libsilk, ~9 min on 2 cores without
# ccache) installed into a fresh venv with onnxruntime and numpy from PyPI: ctest wheel_fresh_venv.
# Needs python3's venv module and PyPI; SILK_WHEEL_TESTS=0 turns it off.
stage "pip wheel in a fresh venv (ctest wheel_fresh_venv)"
if [ "${SILK_WHEEL_TESTS:-1}" = 0 ]; then
  echo "skipped (SILK_WHEEL_TESTS=0)"
else
  (cd build && SILK_TEST_WHEEL=1 ctest --output-on-failure -R '^wheel_fresh_venv$')
fi

# Windows x64 (MinGW-w64 cross-build, run under Wine): where scripts/setup_windows.sh (part of
# `setup.sh --test`) has installed MinGW-w64 and Wine; required in CI (CI=true) and with
# SILK_WINDOWS_TESTS=1, skipped with SILK_WINDOWS_TESTS=0.
stage "Windows x64 build under Wine (scripts/build_windows.sh, scripts/test_windows.sh)"
WINDOWS_TESTS=${SILK_WINDOWS_TESTS:-auto}
[ "$WINDOWS_TESTS" = auto ] && [ "${CI:-}" = true ] && WINDOWS_TESTS=1
if [ "$WINDOWS_TESTS" = 0 ]; then
  echo "skipped (SILK_WINDOWS_TESTS=0)"
elif command -v x86_64-w64-mingw32-g++-posix >/dev/null && { command -v wine64 || [ -x /usr/lib/wine/wine64 ]; } >/dev/null &&
     [ -f .deps/onnxruntime-windows/onnxruntime.dll ]; then
  bash scripts/build_windows.sh && bash scripts/test_windows.sh
elif [ "$WINDOWS_TESTS" = 1 ]; then
  echo "Windows tests required (CI=true or SILK_WINDOWS_TESTS=1) but MinGW-w64 / Wine / onnxruntime.dll are missing: run scripts/setup_windows.sh" >&2
  exit 1
else
  echo "skipped (MinGW-w64, Wine or .deps/onnxruntime-windows missing here: scripts/setup_windows.sh installs them)"
fi

stage "sanitizer build (ASan + UBSan)"
cmake -S . -B build-asan -G Ninja -DCMAKE_BUILD_TYPE=Debug -DSILK_SANITIZE=ON -DSILK_BUILD_BENCH=OFF -DSILK_BUILD_TESTS=ON \
  -DSILK_SHARED_DIR="$SILK_SHARED_DIR" >/dev/null
cmake --build build-asan -j "$JOBS"
(cd build-asan && ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
  ctest --output-on-failure -j "$JOBS" -E 'Slow')
