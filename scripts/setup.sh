#!/usr/bin/env bash
# Installs everything Silk needs on a fresh Debian bookworm machine (idempotent; network only
# through the package managers). Skips apt entirely when every package is already present.
set -euo pipefail

APT_PACKAGES=(
  build-essential cmake ninja-build pkg-config python3
  libopenmesh-dev libglm-dev libtinygltf-dev libstb-dev libcli11-dev nlohmann-json3-dev
  libgtest-dev zlib1g-dev
  clang libclang-rt-14-dev   # libFuzzer targets and the sanitizer build
)

missing=()
for p in "${APT_PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "setup: installing ${missing[*]}"
  SUDO=""
  [ "$(id -u)" -ne 0 ] && SUDO="sudo"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
else
  echo "setup: all system packages present"
fi

# onnxruntime (C library + headers) for engine/runtime and silkgen: not packaged in bookworm.
bash "$(dirname "$0")/fetch_onnxruntime.sh"
