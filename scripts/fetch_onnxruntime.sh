#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Puts onnxruntime's C library and C/C++ headers into .deps/onnxruntime/{lib,include} (gitignored),
# because Debian bookworm has no onnxruntime package. Idempotent: does nothing when already there.
#   library: onnxruntime/capi/libonnxruntime.so.<ver> from the PyPI wheel (same version as the
#            Python package used by export/ and the tests);
#   headers: include/onnxruntime/* from Debian trixie's libonnxruntime-dev, fetched with a
#            temporary apt configuration (the system's apt configuration is never touched).
# Usage: scripts/fetch_onnxruntime.sh [dest]   (default: <repo>/.deps/onnxruntime)
set -euo pipefail
ORT_VERSION=1.22.1
ROOT="$(cd "$(dirname "$0")/.." && pwd)"
DEST="${1:-$ROOT/.deps/onnxruntime}"
PY="${PYTHON:-python3}"

lib_ok() { [ -f "$DEST/lib/libonnxruntime.so.$ORT_VERSION" ] && [ -L "$DEST/lib/libonnxruntime.so" ]; }
inc_ok() { [ -f "$DEST/include/onnxruntime_cxx_api.h" ] && [ -f "$DEST/include/onnxruntime_c_api.h" ]; }
if lib_ok && inc_ok; then
  echo "onnxruntime: $DEST already holds $ORT_VERSION"
  exit 0
fi

TMP="$(mktemp -d)"
trap 'rm -rf "$TMP"' EXIT
mkdir -p "$DEST/lib" "$DEST/include"

if ! lib_ok; then
  echo "onnxruntime: downloading the $ORT_VERSION wheel for this python/platform"
  "$PY" -m pip download -q --no-deps --only-binary=:all: -d "$TMP/wheel" "onnxruntime==$ORT_VERSION"
  whl="$(ls "$TMP"/wheel/onnxruntime-"$ORT_VERSION"-*.whl | head -n1)"
  "$PY" - "$whl" "$DEST/lib" "$ORT_VERSION" <<'EOF'
import sys, zipfile, os
whl, dest, ver = sys.argv[1:4]
name = f"onnxruntime/capi/libonnxruntime.so.{ver}"
with zipfile.ZipFile(whl) as z:
    data = z.read(name)
tmp = os.path.join(dest, f"libonnxruntime.so.{ver}.part")
with open(tmp, "wb") as f:
    f.write(data)
os.chmod(tmp, 0o755)
os.replace(tmp, os.path.join(dest, f"libonnxruntime.so.{ver}"))
EOF
  ln -sfn "libonnxruntime.so.$ORT_VERSION" "$DEST/lib/libonnxruntime.so.1"
  ln -sfn "libonnxruntime.so.1" "$DEST/lib/libonnxruntime.so"
fi

if ! inc_ok; then
  echo "onnxruntime: fetching headers from Debian trixie's libonnxruntime-dev (temporary apt config)"
  # Same mirrors as this machine's Debian sources (deb822 *.sources and one-line *.list),
  # security archives left out, suite replaced by trixie.
  uris="$(cat /etc/apt/sources.list.d/*.sources 2>/dev/null | sed -n 's/^URIs:[[:space:]]*//p';
          cat /etc/apt/sources.list /etc/apt/sources.list.d/*.list 2>/dev/null |
            sed -n 's/^deb[[:space:]]\+\(\[[^]]*\][[:space:]]\+\)\?\([^[:space:]]\+\).*/\2/p' || true)"
  uris="$(printf '%s\n' $uris | grep -E '/debian/?$' | grep -v security | sort -u || true)"
  [ -n "$uris" ] || uris="http://deb.debian.org/debian"
  keyring=/usr/share/keyrings/debian-archive-keyring.gpg
  mkdir -p "$TMP/apt/lists/partial" "$TMP/apt/cache/archives/partial" "$TMP/deb"
  for u in $uris; do echo "deb [signed-by=$keyring] $u trixie main"; done > "$TMP/apt/sources.list"
  APT_OPTS=(-o "Dir::Etc::SourceList=$TMP/apt/sources.list" -o Dir::Etc::SourceParts=/dev/null
            -o "Dir::State::Lists=$TMP/apt/lists" -o "Dir::Cache=$TMP/apt/cache"
            -o Dir::State::status=/dev/null -o Debug::NoLocking=1 -o APT::Get::List-Cleanup=0)
  # Downloads go to our own temp folder, which the _apt sandbox user cannot write.
  [ "$(id -u)" -eq 0 ] && APT_OPTS+=(-o APT::Sandbox::User=root)
  apt-get "${APT_OPTS[@]}" update -qq
  (cd "$TMP/deb" && apt-get "${APT_OPTS[@]}" download -qq libonnxruntime-dev)
  dpkg-deb -x "$TMP"/deb/libonnxruntime-dev_*.deb "$TMP/x"
  cp -r "$TMP"/x/usr/include/onnxruntime/. "$DEST/include/"
  dpkg-deb -f "$TMP"/deb/libonnxruntime-dev_*.deb Version > "$DEST/include/DEBIAN_VERSION"
fi
echo "$ORT_VERSION" > "$DEST/VERSION"
echo "onnxruntime: library $ORT_VERSION (PyPI wheel), headers $(cat "$DEST/include/DEBIAN_VERSION") (Debian trixie) in $DEST"
