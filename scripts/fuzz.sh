#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Runs the libFuzzer targets (default: all of fuzz/*_fuzzer.cpp) one after another (one core), each for the given time, with a
# fresh scratch corpus per target seeded from fuzz/corpus/<target> (+ matching bad inputs).
# Usage: scripts/fuzz.sh [-b] [seconds_per_target=600] [target...]
#   -b  detach (setsid nohup) and return at once; follow /tmp/fuzzlogs/<target>.log
# Needs the clang build: CC=clang CXX=clang++ cmake -S . -B build-fuzz -G Ninja \
#   -DSILK_BUILD_FUZZERS=ON -DSILK_SANITIZE=ON -DSILK_BUILD_TESTS=OFF -DSILK_BUILD_APPS=OFF -DSILK_BUILD_BENCH=OFF
set -euo pipefail
repo="$(cd "$(dirname "$0")/.." && pwd)"
if [[ "${1:-}" == "-b" ]]; then
  shift
  mkdir -p /tmp/fuzzlogs
  setsid nohup "$0" "$@" > /tmp/fuzzlogs/fuzz.sh.log 2>&1 < /dev/null &
  echo "fuzzing in the background (pid $!); logs in /tmp/fuzzlogs/"
  exit 0
fi
secs="${1:-600}"
shift || true
targets=("$@")
if [[ ${#targets[@]} -eq 0 ]]; then
  for src in "$repo"/fuzz/*_fuzzer.cpp; do targets+=("$(basename "$src" .cpp)"); done  # every target
fi
build="${BUILD_DIR:-$repo/build-fuzz}"
source "$repo/scripts/shared_dir.sh"
shared=$(silk_shared_dir) || exit 2
work=/tmp/fuzzwork
logs=/tmp/fuzzlogs
mkdir -p "$work" "$logs"
for t in "${targets[@]}"; do
  exe="$build/fuzz/$t"
  if [[ ! -x "$exe" ]]; then
    echo "$t: $exe not built, skipped" | tee "$logs/$t.log"
    continue
  fi
  rm -rf "${work:?}/$t"
  mkdir -p "$work/$t"
  cp "$repo/fuzz/corpus/$t/"* "$work/$t/" 2>/dev/null || true
  ext="${t%%_*}"  # obj, ply, stl, off, gltf, glb
  if [[ -d "$shared/corpus/bad" ]]; then
    find "$shared/corpus/bad" -maxdepth 1 -name "*.$ext" -size -100k -exec cp {} "$work/$t/" \;
  fi
  echo "== $t: ${secs}s, corpus $work/$t, started $(date -u +%FT%TZ)" > "$logs/$t.log"
  set +e
  "$exe" "$work/$t" -max_total_time="$secs" -rss_limit_mb=2048 -timeout=10 \
    -artifact_prefix="$logs/$t-" >> "$logs/$t.log" 2>&1
  rc=$?
  set -e
  echo "== $t: exit code $rc, finished $(date -u +%FT%TZ)" >> "$logs/$t.log"
done
echo "all fuzz runs done"
