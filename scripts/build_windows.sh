#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Cross-builds Silk for Windows x64 with MinGW-w64 into build-windows/ and assembles
# build-windows/dist/silk-windows-x64/ (+ .zip): silkgen.exe, silktok.exe, libsilk.dll,
# onnxruntime.dll with its licence and notices, the bundled model, README.txt, LICENSE.txt. Installs nothing: scripts/setup_windows.sh does.
# Usage: scripts/build_windows.sh [extra cmake args]
set -euo pipefail
cd "$(dirname "$0")/.."
ROOT="$PWD"
JOBS=${JOBS:-$(nproc)}
B=build-windows
ORT_DLL_DIR="${ONNXRUNTIME_DLL_DIR:-$ROOT/.deps/onnxruntime-windows}"
command -v x86_64-w64-mingw32-g++-posix >/dev/null ||
  { echo "build_windows: x86_64-w64-mingw32-g++-posix not found (run scripts/setup_windows.sh)" >&2; exit 1; }
[ -f "$ORT_DLL_DIR/onnxruntime.dll" ] ||
  { echo "build_windows: $ORT_DLL_DIR/onnxruntime.dll not found (run scripts/setup_windows.sh)" >&2; exit 1; }

cmake -S . -B "$B" -G Ninja -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_TOOLCHAIN_FILE="$ROOT/cmake/windows/mingw-w64-x86_64.cmake" \
  -DONNXRUNTIME_DLL_DIR="$ORT_DLL_DIR" -DSILK_BUILD_BENCH=OFF -DSILK_BUILD_FUZZERS=OFF "$@" >/dev/null
cmake --build "$B" -j "$JOBS"

DIST="$B/dist/silk-windows-x64"
rm -rf "$B/dist"
mkdir -p "$DIST/models"
cp "$B/apps/silktok.exe" "$B/engine/libsilk.dll" "$DIST/"
[ -f "$B/apps/silkgen.exe" ] && cp "$B/apps/silkgen.exe" "$ORT_DLL_DIR/onnxruntime.dll" "$DIST/"
[ -f models/default/model.json ] && cp -r models/default "$DIST/models/default"
x86_64-w64-mingw32-strip "$DIST"/*.exe "$DIST/libsilk.dll"
cp engine/include/silk/silk.h engine/include/silk/silk.hpp "$DIST/"
cp LICENSE "$DIST/LICENSE.txt"  # MIT; the bundled model's data licence is models/default/LICENSE.md
if [ -f "$DIST/onnxruntime.dll" ]; then  # onnxruntime's own licence (MIT) and notices travel with its DLL
  for f in LICENSE ThirdPartyNotices.txt; do
    [ -f "$ORT_DLL_DIR/$f" ] ||
      { echo "build_windows: $ORT_DLL_DIR/$f not found (rerun scripts/setup_windows.sh)" >&2; exit 1; }
  done
  cp "$ORT_DLL_DIR/LICENSE" "$DIST/onnxruntime-LICENSE.txt"
  cp "$ORT_DLL_DIR/ThirdPartyNotices.txt" "$DIST/onnxruntime-ThirdPartyNotices.txt"
fi
cp "$B/engine/libsilk.dll.a" "$DIST/"
sed "s/@ORT_VERSION@/$(cat "$ORT_DLL_DIR/VERSION" 2>/dev/null || echo ?)/" scripts/windows_readme.txt > "$DIST/README.txt"

# Only the C API leaves libsilk.dll (onnxruntime's custom-op entry is libsilk_ops', not shipped here).
exports="$(x86_64-w64-mingw32-objdump -p "$DIST/libsilk.dll" |
           sed -n '/\[Ordinal\/Name Pointer\] Table/,/^$/p' | sed -n 's/^[[:space:]]*\[ *[0-9]*\] //p')"
bad="$(echo "$exports" | grep -v -e '^silk_' || true)"
if [ -z "$exports" ] || [ -n "$bad" ]; then
  echo "build_windows: libsilk.dll exports more than silk_*:" >&2; echo "$bad" | head >&2; exit 1
fi
echo "build_windows: libsilk.dll exports $(echo "$exports" | wc -l) symbols, all silk_*; imports:" \
  $(x86_64-w64-mingw32-objdump -p "$DIST/libsilk.dll" | sed -n 's/^[[:space:]]*DLL Name: //p')
(cd "$B/dist" && rm -f silk-windows-x64.zip && zip -qr silk-windows-x64.zip silk-windows-x64)
echo "build_windows: $DIST ($(ls "$DIST" | tr '\n' ' '))"
echo "build_windows: $B/dist/silk-windows-x64.zip ($(du -h "$B/dist/silk-windows-x64.zip" | cut -f1))"
