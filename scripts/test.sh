#!/usr/bin/env bash
# Builds and runs every test: the normal build (unit, golden, dev-corpus, CLI and bad-input
# tests), then an ASan + UBSan build of the same tests (the slow dev-corpus suites excluded).
set -euo pipefail
cd "$(dirname "$0")/.."
JOBS=${JOBS:-$(nproc)}

bash scripts/build.sh
(cd build && ctest --output-on-failure -j "$JOBS")

echo "=== export/ (pytest, through build/engine/libsilk.so) ==="
SILK_LIBRARY="$PWD/build/engine/libsilk.so" python3 -m pytest -q export/tests

echo "=== sanitizer build (ASan + UBSan) ==="
cmake -S . -B build-asan -G Ninja -DCMAKE_BUILD_TYPE=Debug -DSILK_SANITIZE=ON -DSILK_BUILD_BENCH=OFF >/dev/null
cmake --build build-asan -j "$JOBS"
(cd build-asan && ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
  ctest --output-on-failure -j "$JOBS" -E 'Slow')
