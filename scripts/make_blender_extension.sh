#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Packages the add-on as Blender extensions (Blender 4.2+), one zip per platform, each carrying only
# that platform's libraries, laid out as Blender's own `extension build --split-platforms` does
# (blender_manifest.toml at the zip's root, `platforms` = that one platform, `version` = silk.h's):
#   silk_blender-<version>-linux_x64.zip    from the build tree (libsilk.so + libonnxruntime,
#                                           through scripts/make_blender_addon.sh)
#   silk_blender-<version>-windows_x64.zip  when the Windows cross-build's folder exists
#                                           (scripts/build_windows.sh: libsilk.dll, onnxruntime.dll
#                                           and any other DLL beside them)
# Both carry the same Python files and the same bundled model.
# Usage: scripts/make_blender_extension.sh [build dir] [output dir] [model dir] [windows dist dir]
#   defaults: build, <build>/extensions, models/default, build-windows/dist/silk-windows-x64
set -euo pipefail
ROOT="$(cd "$(dirname "$0")/.." && pwd)"
BUILD="$(cd "${1:-$ROOT/build}" && pwd)"
OUTDIR="${2:-$BUILD/extensions}"
MODEL="${3:-$ROOT/models/default}"
WINDIST="${4:-$ROOT/build-windows/dist/silk-windows-x64}"
mkdir -p "$OUTDIR"
OUTDIR="$(cd "$OUTDIR" && pwd)"

# The linux-x64 add-on folder (Python files, vendored binding, libraries, model, stamped manifest).
bash "$ROOT/scripts/make_blender_addon.sh" "$BUILD" "$OUTDIR/linux_x64.zip" "$MODEL" >/dev/null
rm -f "$OUTDIR/linux_x64.zip"
LINUX="$OUTDIR/linux_x64_stage/silk_blender"
VERSION=$(sed -n 's/^version = "\(.*\)"$/\1/p' "$LINUX/blender_manifest.toml")

# package FOLDER PLATFORM: stamps `platforms` and zips the folder's contents (manifest at the root).
package() {
  local dir=$1 platform=$2 zip
  zip="$OUTDIR/silk_blender-$VERSION-${platform/-/_}.zip"
  python3 - "$dir/blender_manifest.toml" "$platform" <<'PY'
import re, sys
path, platform = sys.argv[1], sys.argv[2]
text, n = re.subn(r'^platforms = \[.*\]$', f'platforms = ["{platform}"]', open(path).read(), count=1, flags=re.M)
if n != 1:
    sys.exit("make_blender_extension: no platforms line in blender_manifest.toml")
open(path, "w").write(text)
PY
  rm -f "$zip"
  (cd "$dir" && python3 -m zipfile -c "$zip" $(ls -A))
  echo "$zip"
}

package "$LINUX" linux-x64

if [ -f "$WINDIST/libsilk.dll" ]; then
  WIN="$OUTDIR/windows_x64_stage/silk_blender"
  rm -rf "$OUTDIR/windows_x64_stage" && mkdir -p "$OUTDIR/windows_x64_stage"
  cp -r "$LINUX" "$WIN"
  rm -rf "$WIN/silk_mesh/lib" && mkdir -p "$WIN/silk_mesh/lib"
  cp "$WINDIST"/*.dll "$WIN/silk_mesh/lib/"
  [ -f "$WIN/silk_mesh/lib/onnxruntime.dll" ] ||
    echo "make_blender_extension: no onnxruntime.dll in $WINDIST: the Windows extension cannot generate" >&2
  package "$WIN" windows-x64
else
  echo "make_blender_extension: no $WINDIST/libsilk.dll (scripts/build_windows.sh makes it): linux-x64 only" >&2
fi
