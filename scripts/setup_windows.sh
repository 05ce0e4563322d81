#!/usr/bin/env bash
# Installs what the Windows x64 cross-build and its Wine tests need (scripts/build_windows.sh,
# scripts/test_windows.sh) on Debian bookworm, on top of scripts/setup.sh's packages: MinGW-w64
# (posix threads), zlib for MinGW, Wine 8 (64-bit), GoogleTest's sources; and onnxruntime.dll
# from PyPI's win_amd64 wheel (same pinned version as the Linux library) into
# .deps/onnxruntime-windows. Idempotent; network only through apt and pip.
set -euo pipefail
REPO="$(cd "$(dirname "$0")/.." && pwd)"
APT_PACKAGES=(g++-mingw-w64-x86-64-posix binutils-mingw-w64-x86-64 libz-mingw-w64-dev wine64 googletest zip
              libtinygltf-dev libcli11-dev nlohmann-json3-dev)
missing=()
for p in "${APT_PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "setup_windows: installing ${missing[*]}"
  SUDO=""
  [ "$(id -u)" -ne 0 ] && SUDO="sudo"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
else
  echo "setup_windows: all system packages present"
fi

# onnxruntime's C/C++ headers: the Linux build's (scripts/fetch_onnxruntime.sh).
bash "$REPO/scripts/fetch_onnxruntime.sh"
ORT_VERSION="$(sed -n 's/^ORT_VERSION=//p' "$REPO/scripts/fetch_onnxruntime.sh")"
DEST="${1:-$REPO/.deps/onnxruntime-windows}"
if [ -f "$DEST/onnxruntime.dll" ] && [ "$(cat "$DEST/VERSION" 2>/dev/null)" = "$ORT_VERSION" ]; then
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
with zipfile.ZipFile(whl) as z:
    data = z.read("onnxruntime/capi/onnxruntime.dll")
with open(os.path.join(dest, "onnxruntime.dll.part"), "wb") as f:
    f.write(data)
os.replace(os.path.join(dest, "onnxruntime.dll.part"), os.path.join(dest, "onnxruntime.dll"))
PY
echo "$ORT_VERSION" > "$DEST/VERSION"
echo "setup_windows: onnxruntime.dll $ORT_VERSION in $DEST"
