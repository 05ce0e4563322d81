#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Installs what Silk needs on a fresh Debian bookworm machine (idempotent; network only through
# the package managers). Two levels:
#   bash scripts/setup.sh          what scripts/demo.sh runs: the compiler and libraries for libsilk,
#                                  silkgen and silktok, and onnxruntime (no Python packages, no Blender)
#   bash scripts/setup.sh --test   that, plus everything scripts/test.sh runs (the README's test command)
# To add a test dependency, add it to one of the TEST_* lists below.
set -euo pipefail
REPO="$(cd "$(dirname "$0")/.." && pwd)"
cd "$REPO"
LEVEL=demo
case "${1:-}" in
  "") ;;
  --test) LEVEL=test ;;
  *) echo "usage: scripts/setup.sh [--test]  (unknown argument '$1')" >&2; exit 2 ;;
esac

# ---- what the demo needs ----------------------------------------------------------------------
DEMO_APT=(
  build-essential cmake ninja-build pkg-config python3
  python3-pip                # scripts/fetch_onnxruntime.sh: pip download of the onnxruntime wheel
  libtinygltf-dev libstb-dev libcli11-dev nlohmann-json3-dev zlib1g-dev
)

# ---- what the tests need on top (--test) ------------------------------------------------------
TEST_APT=(
  libgtest-dev libopenmesh-dev  # tests/ (OpenMesh: tests/oracle, the independent mesh-verdict check)
  clang libclang-rt-14-dev   # libFuzzer targets (scripts/fuzz.sh)
  blender python3-numpy      # the add-on's headless test (tests/blender; bookworm: Blender 3.4.1);
                             # numpy for Blender's own glTF importer
  xvfb xauth                 # the add-on's modal test: a real Blender window on a private X server
  python3-venv               # the bpy venvs below
  patchelf                   # scripts/make_blender_addon.sh: bundled libraries find each other ($ORIGIN)
  clang-format-14            # scripts/format.sh (.clang-format): the pinned C/C++ formatter
)
# pip requirement files installed into python3 (Debian's is "externally managed": PEP 668).
TEST_PIP_REQUIREMENTS=(
  export/requirements.txt    # export/: dataset through libsilk, training (torch), ONNX export, pytest
  scripts/format-requirements.txt  # scripts/format.sh: ruff, pinned
)
# Editable installs into python3 (the command line tools they define land on the PATH).
TEST_PIP_EDITABLE=(
  export                     # silk-export
)
# Blender as a Python module (PyPI's bpy, Python 3.11 only), one venv each: build/bpy-<major.minor>;
# the versions are listed in tests/blender/bpy_versions.txt (ctest blender_addon_bpy_<major.minor>).
mapfile -t TEST_BPY_VERSIONS < <(sed 's/#.*//' tests/blender/bpy_versions.txt | awk 'NF {print $1}')

# shellcheck source=apt_install_missing.sh
source "$REPO/scripts/apt_install_missing.sh"

pip_requirements() {  # pip install -r FILE into python3 unless every pinned version is there
  local req=$1
  if python3 - "$req" <<'PY' 2>/dev/null
import importlib.metadata as m, sys
for line in open(sys.argv[1]):
    line = line.split("#")[0].strip()
    if line:
        name, _, ver = line.partition("==")
        have = m.version(name)
        if ver and have.split("+")[0] != ver:
            sys.exit(1)
PY
  then
    echo "setup: Python packages of $req present"
  else
    echo "setup: installing Python packages ($req)"
    # PIP_BREAK_SYSTEM_PACKAGES: Debian's own python3 is "externally managed" (PEP 668).
    PIP_BREAK_SYSTEM_PACKAGES=1 python3 -m pip install -q --disable-pip-version-check -r "$req"
  fi
}

pip_editable() {  # pip install -e DIR into python3 unless the installed copy already points here
  local dir="$REPO/$1" name
  name=$(sed -n 's/^name *= *"\(.*\)"/\1/p' "$dir/pyproject.toml" | head -1)
  if python3 - "$name" "$dir" <<'PY' 2>/dev/null
import importlib.metadata as m, json, sys
dist = m.distribution(sys.argv[1])
url = json.loads(dist.read_text("direct_url.json") or "{}").get("url", "")
sys.exit(0 if url.rstrip("/").endswith(sys.argv[2].rstrip("/")) else 1)
PY
  then
    echo "setup: $name installed (editable, this checkout)"
  else
    echo "setup: installing $1 (pip install -e: $name)"
    PIP_BREAK_SYSTEM_PACKAGES=1 python3 -m pip install -q --disable-pip-version-check --no-deps -e "$dir"
  fi
}

bpy_venv() {  # build/bpy-<major.minor> with bpy==VERSION (PyPI's wheels need Python 3.11)
  local ver=$1 venv
  venv="$REPO/build/bpy-$(echo "$ver" | cut -d. -f1,2)"
  if [ -x "$venv/bin/python" ] && "$venv/bin/python" -c "import importlib.metadata as m, sys; sys.exit(m.version('bpy') != '$ver')" 2>/dev/null; then
    echo "setup: bpy $ver present ($venv)"
    return
  fi
  if ! python3 -c 'import sys; sys.exit(sys.version_info[:2] != (3, 11))'; then
    echo "setup: python3 is $(python3 -V 2>&1 | cut -d' ' -f2), PyPI's bpy needs 3.11: no $venv (its ctest is skipped)"
    return
  fi
  echo "setup: installing bpy $ver into $venv"
  rm -rf "$venv"
  python3 -m venv "$venv"
  "$venv/bin/python" -m pip install -q --disable-pip-version-check "bpy==$ver"
}

if [ "$LEVEL" = test ]; then
  apt_install_missing setup "${DEMO_APT[@]}" "${TEST_APT[@]}"
else
  apt_install_missing setup "${DEMO_APT[@]}"
fi

# onnxruntime (C library + headers) for engine/runtime and silkgen: not packaged in bookworm.
bash "$REPO/scripts/fetch_onnxruntime.sh"

[ "$LEVEL" = test ] || exit 0
for req in "${TEST_PIP_REQUIREMENTS[@]}"; do pip_requirements "$req"; done
for dir in "${TEST_PIP_EDITABLE[@]}"; do pip_editable "$dir"; done
for ver in "${TEST_BPY_VERSIONS[@]}"; do bpy_venv "$ver"; done
# The Windows x64 cross-build and its Wine tests (MinGW-w64, Wine, onnxruntime.dll).
bash "$REPO/scripts/setup_windows.sh"
