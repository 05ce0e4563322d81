#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Installs what the Windows x64 cross-build and its Wine tests need (scripts/build_windows.sh,
# scripts/test_windows.sh) on Debian bookworm, on top of scripts/setup.sh (run it first: the
# header-only libraries, GoogleTest's sources and onnxruntime's headers come from there):
# MinGW-w64 (posix threads), zlib for MinGW, Wine 8 (64-bit), zip; and onnxruntime.dll from
# PyPI's win_amd64 wheel (the Linux library's pinned version) into .deps/onnxruntime-windows, with its
# licence and third-party notices (shipped beside it in the zip).
# Idempotent and quick when everything is there (no apt, no network); network only through apt
# and pip. Usage: scripts/setup_windows.sh [dest for onnxruntime.dll]
set -euo pipefail
REPO="$(cd "$(dirname "$0")/.." && pwd)"
# shellcheck source=apt_install_missing.sh
source "$REPO/scripts/apt_install_missing.sh"
apt_install_missing setup_windows g++-mingw-w64-x86-64-posix binutils-mingw-w64-x86-64 libz-mingw-w64-dev wine64 zip
for h in /usr/include/tiny_gltf.h /usr/include/CLI/CLI.hpp /usr/include/nlohmann/json.hpp /usr/src/googletest/CMakeLists.txt; do
  [ -e "$h" ] || { echo "setup_windows: $h missing: run scripts/setup.sh first" >&2; exit 1; }
done

# onnxruntime's C/C++ headers: the Linux build's (scripts/fetch_onnxruntime.sh; a no-op when there).
bash "$REPO/scripts/fetch_onnxruntime.sh"
ORT_VERSION="$(sed -n 's/^ORT_VERSION=//p' "$REPO/scripts/fetch_onnxruntime.sh")"
DEST="${1:-$REPO/.deps/onnxruntime-windows}"
if [ -f "$DEST/onnxruntime.dll" ] && [ -f "$DEST/ThirdPartyNotices.txt" ] &&
  [ "$(cat "$DEST/VERSION" 2>/dev/null)" = "$ORT_VERSION" ]; then
  echo "setup_windows: $DEST already holds onnxruntime.dll $ORT_VERSION"
  exit 0
fi
TMP="$(mktemp -d)"
trap 'rm -rf "$TMP"' EXIT
echo "setup_windows: downloading the onnxruntime $ORT_VERSION win_amd64 wheel"
python3 -m pip download -q --no-deps --only-binary=:all: --platform win_amd64 --python-version 3.11 \
  -d "$TMP" "onnxruntime==$ORT_VERSION"
mkdir -p "$DEST"
python3 - "$TMP"/onnxruntime-"$ORT_VERSION"-*.whl "$DEST" <<'PY'
import os, sys, zipfile
whl, dest = sys.argv[1:3]
# The DLL and, to ship beside it, onnxruntime's licence (MIT) and its third-party notices.
parts = {"onnxruntime/capi/onnxruntime.dll": "onnxruntime.dll", "onnxruntime/LICENSE": "LICENSE",
         "onnxruntime/ThirdPartyNotices.txt": "ThirdPartyNotices.txt"}
with zipfile.ZipFile(whl) as z:
    for member, name in parts.items():
        with open(os.path.join(dest, name + ".part"), "wb") as f:
            f.write(z.read(member))
        os.replace(os.path.join(dest, name + ".part"), os.path.join(dest, name))
PY
echo "$ORT_VERSION" > "$DEST/VERSION"
echo "setup_windows: onnxruntime.dll $ORT_VERSION in $DEST"
