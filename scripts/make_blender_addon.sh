#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Makes the installable Blender add-on zip: apps/blender/silk_blender + the Python binding
# bindings/python/silk_mesh, copied unchanged into silk_blender/silk_mesh/, with libsilk (installed
# copy, $ORIGIN RPATH), onnxruntime and the other non-system libraries it needs in silk_mesh/lib/
# and the bundled model in silk_mesh/model/ (where silk_mesh looks for them).
# Usage: scripts/make_blender_addon.sh [build dir] [output zip] [model dir]
#   defaults: build, <build>/silk_blender.zip, models/default
# The windows-x64 variant, from the Windows zip's folder (scripts/build_windows.sh): libsilk.dll
# and onnxruntime.dll in silk_mesh/lib/, the folder's models/default, manifest platform windows-x64:
#   scripts/make_blender_addon.sh --windows [dist folder] [output zip]
#   defaults: build-windows/dist/silk-windows-x64, build-windows/dist/silk_blender-windows-x64.zip
set -euo pipefail
ROOT="$(cd "$(dirname "$0")/.." && pwd)"
WINDOWS=0
if [ "${1:-}" = "--windows" ]; then
  WINDOWS=1
  shift
  DIST="$(cd "${1:-$ROOT/build-windows/dist/silk-windows-x64}" && pwd)"
  OUT="${2:-$(dirname "$DIST")/silk_blender-windows-x64.zip}"
  MODEL="$DIST/models/default"
else
  BUILD="$(cd "${1:-$ROOT/build}" && pwd)"
  OUT="${2:-$BUILD/silk_blender.zip}"
  MODEL="${3:-$ROOT/models/default}"
fi
# Scratch folder beside the zip, so two makes with different outputs (ctest runs blender_addon
# and blender_addon_modal in parallel) never share one.
mkdir -p "$(dirname "$OUT")"
OUT="$(cd "$(dirname "$OUT")" && pwd)/$(basename "$OUT")"
STAGE="${OUT%.zip}_stage"
rm -rf "$STAGE"
ADDON="$STAGE/silk_blender"
BINDING="$ADDON/silk_mesh"  # vendored byte for byte (ctest blender_addon_vendored_binding checks the zip)
mkdir -p "$BINDING/lib"
# The add-on is GPL-3.0-or-later (its LICENSE, as Blender requires); the vendored binding keeps
# the repository's MIT licence beside it.
cp "$ROOT"/apps/blender/silk_blender/*.py "$ROOT/apps/blender/silk_blender/blender_manifest.toml" \
   "$ROOT/apps/blender/silk_blender/LICENSE" "$ADDON/"
cp "$ROOT"/bindings/python/silk_mesh/*.py "$ROOT/bindings/python/silk_mesh/README.md" "$BINDING/"
cp "$ROOT/LICENSE" "$BINDING/LICENSE"
# The add-on's version is Silk's (silk.h, the one version source): stamped into the manifest and bl_info.
python3 - "$ROOT/engine/include/silk/silk.h" "$ADDON" <<'PY'
import re, sys
header, addon = sys.argv[1], sys.argv[2]
ver = [re.search(rf"^#define SILK_VERSION_{k} (\d+)$", open(header).read(), re.M).group(1) for k in ("MAJOR", "MINOR", "PATCH")]
for name, pattern, repl in (("blender_manifest.toml", r'^version = ".*"$', f'version = "{".".join(ver)}"'),
                            ("__init__.py", r'^    "version": \(.*?\),.*$', f'    "version": ({", ".join(ver)}),')):
    path = f"{addon}/{name}"
    text, n = re.subn(pattern, repl, open(path).read(), count=1, flags=re.M)
    if n != 1:
        sys.exit(f"make_blender_addon: no version line in {name} to stamp")
    open(path, "w").write(text)
PY
if [ "$WINDOWS" = 1 ]; then
  # silk_mesh loads onnxruntime.dll first, then libsilk.dll, both by full path from lib/.
  cp "$DIST/libsilk.dll" "$DIST/onnxruntime.dll" "$BINDING/lib/"
  cp "$DIST/onnxruntime-LICENSE.txt" "$DIST/onnxruntime-ThirdPartyNotices.txt" "$BINDING/lib/"  # its licence travels with it
  sed -i 's/^platforms = .*/platforms = ["windows-x64"]/' "$ADDON/blender_manifest.toml"
else
command -v patchelf >/dev/null || { echo "make_blender_addon: patchelf is needed (apt-get install patchelf)" >&2; exit 1; }
cmake --install "$BUILD" --prefix "$STAGE/prefix" >/dev/null
LIBDIR=$(dirname "$(ls "$STAGE"/prefix/lib*/libsilk.so.* | head -1)")
# One file per library, under its soname (zip has no symlinks); libsilk without debug info.
SILK_SONAME=$(objdump -p "$LIBDIR/libsilk.so" | awk '/SONAME/ {print $2}')
cp -L "$LIBDIR/libsilk.so" "$BINDING/lib/$SILK_SONAME"
strip --strip-debug "$BINDING/lib/$SILK_SONAME"
ORT_SONAME=$(objdump -p "$LIBDIR/libsilk.so" | awk '/NEEDED/ && /onnxruntime/ {print $2}')
cp -L "$LIBDIR/$ORT_SONAME" "$BINDING/lib/$ORT_SONAME"
# Shared libraries libsilk needs that a stock Blender machine may lack (not libc/libstdc++).
for dep in $(ldd "$LIBDIR/libsilk.so" | awk '/=> \// {print $3}'); do
  case "$(basename "$dep")" in
    libc.so*|libm.so*|libstdc++.so*|libgcc_s.so*|libpthread.so*|libdl.so*|librt.so*|libz.so*|libonnxruntime*) ;;
    *) cp -L "$dep" "$BINDING/lib/"
       # It may need another bundled library (libtinygltf needs libstb): search its own folder.
       patchelf --set-rpath '$ORIGIN' "$BINDING/lib/$(basename "$dep")" ;;
  esac
done
fi
if [ -f "$MODEL/model.json" ]; then
  mkdir -p "$BINDING/model"
  python3 - "$MODEL" "$BINDING/model" <<'PY'
import json, shutil, sys
src, dst = sys.argv[1], sys.argv[2]
meta = json.load(open(f"{src}/model.json"))
files = {"model.json", meta.get("files", {}).get("encoder", "encoder.onnx"), meta.get("files", {}).get("decoder", "decoder.onnx")}
int8 = meta.get("files", {}).get("decoder_int8")
if int8:
    files.add(int8)
# The fp16- and int8-cache variants of those decoders (files.kv_fp16, files.kv_int8), when the
# model has them.
for kv in ("kv_fp16", "kv_int8"):
    for key in ("decoder", "decoder_int8"):
        variant = meta.get("files", {}).get(kv, {}).get(key)
        if variant:
            files.add(variant)
for f in sorted(files) + ["MODEL_CARD.md", "LICENSE.md"]:  # LICENSE.md: the training data's licence
    try:
        shutil.copy(f"{src}/{f}", f"{dst}/{f}")
    except FileNotFoundError:
        pass
PY
else
  echo "make_blender_addon: no model at $MODEL (the add-on then needs model_dir)" >&2
fi
rm -f "$OUT"
(cd "$STAGE" && python3 -m zipfile -c "$OUT" silk_blender)
echo "$OUT"
