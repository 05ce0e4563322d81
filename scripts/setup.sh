#!/usr/bin/env bash
# Installs everything Silk needs on a fresh Debian bookworm machine (idempotent; network only
# through the package managers). Skips apt entirely when every package is already present.
set -euo pipefail
REPO="$(cd "$(dirname "$0")/.." && pwd)"
cd "$REPO"

APT_PACKAGES=(
  build-essential cmake ninja-build pkg-config python3
  python3-pip                # scripts/fetch_onnxruntime.sh: pip download of the onnxruntime wheel
  libtinygltf-dev libstb-dev libcli11-dev nlohmann-json3-dev zlib1g-dev
  libgtest-dev libopenmesh-dev  # tests only (OpenMesh: tests/oracle, the independent mesh-verdict check)
  clang libclang-rt-14-dev   # libFuzzer targets and the sanitizer build
  blender python3-numpy      # the add-on's headless test (tests/blender; bookworm: Blender 3.4.1);
                             # numpy for Blender's own glTF importer
  xvfb xauth                 # the add-on's modal test: a real Blender window on a private X server
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
bash "$REPO/scripts/fetch_onnxruntime.sh"

# Python side (export/: dataset through libsilk, training, ONNX export, evaluation; pytest).
# PyPI's torch is the CUDA build (~3 GB) and runs on the CPU. Quick no-op when installed.
if python3 - <<'PY' 2>/dev/null
import importlib.metadata as m, sys
want = {}
for line in open("export/requirements.txt"):
    line = line.split("#")[0].strip()
    if line:
        name, _, ver = line.partition("==")
        want[name] = ver
for name, ver in want.items():
    have = m.version(name)
    if ver and have.split("+")[0] != ver:
        sys.exit(1)
PY
then
  echo "setup: Python packages present"
else
  echo "setup: installing Python packages (export/requirements.txt)"
  # PIP_BREAK_SYSTEM_PACKAGES: Debian's own python3 is "externally managed" (PEP 668).
  PIP_BREAK_SYSTEM_PACKAGES=1 python3 -m pip install -q --disable-pip-version-check -r export/requirements.txt
fi

# The export/ package itself (editable), so `silk-export` is on the PATH. Quick no-op when the
# installed copy already points at this checkout.
if python3 - "$REPO/export" <<'PY' 2>/dev/null
import importlib.metadata as m, json, sys
dist = m.distribution("silk-export")
url = json.loads(dist.read_text("direct_url.json") or "{}").get("url", "")
sys.exit(0 if url.rstrip("/").endswith(sys.argv[1].rstrip("/")) else 1)
PY
then
  echo "setup: silk-export installed (editable, this checkout)"
else
  echo "setup: installing export/ (pip install -e export: the silk-export command)"
  PIP_BREAK_SYSTEM_PACKAGES=1 python3 -m pip install -q --disable-pip-version-check --no-deps -e "$REPO/export"
fi
