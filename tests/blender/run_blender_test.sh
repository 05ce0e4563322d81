# SPDX-License-Identifier: MIT
# ctest blender_addon / blender_addon_modal / blender_addon_bpy_* / blender_extension_bpy_*: builds
# the add-on zip (bundled model = the tiny test model) and runs a Blender test against it:
# `headless` (Debian's blender -b, test_silk_addon.py), `modal` (a real window under Xvfb with event
# simulation, test_silk_addon_modal.py), `screenshot` (the Silk tab's picture for docs/blender.md,
# screenshot_sidebar.py, windowed under Xvfb), `bpy` (test_silk_addon.py in PyPI's bpy module, the venv
# $SILK_BPY_VENV that scripts/setup.sh --test makes; SILK_ADDON_KIND=extension installs the
# linux-x64 extension zip of scripts/make_blender_extension.sh through the extensions API, after
# Blender's own `extension validate` of it), or `vendored` (the zip's silk_mesh is
# bindings/python/silk_mesh unchanged; no Blender). Exit 77 (ctest: skipped) where Blender, for
# `modal` xvfb-run, or for `bpy` the venv is not installed.
# Usage: run_blender_test.sh headless|modal|screenshot|bpy|vendored BUILD_DIR SOURCE_DIR WORK_DIR SILKGEN DEV_MESH
set -euo pipefail
MODE=$1 BUILD=$2 SRC=$3 WORK=$4 SILKGEN=$5 DEV_MESH=$6
MODEL=${SILK_ADDON_MODEL:-$SRC/tests/models/tiny}  # the docs picture uses models/default
if [ "$MODE" = vendored ]; then  # the zip's copy of bindings/python/silk_mesh (no Blender needed)
  rm -rf "$WORK" && mkdir -p "$WORK"
  bash "$SRC/scripts/make_blender_addon.sh" "$BUILD" "$WORK/silk_blender.zip" "$MODEL" >/dev/null
  exec python3 "$SRC/tests/blender/check_vendored_binding.py" "$WORK/silk_blender.zip" "$SRC"
fi
MESH_CHECK="$(dirname "$DEV_MESH")/../../tools/mesh_check.py"  # ../shared/tools, beside the corpus
KIND=${SILK_ADDON_KIND:-addon}
if [ "$MODE" = bpy ]; then
  VENV=${SILK_BPY_VENV:?SILK_BPY_VENV names the bpy venv}
  if [ ! -x "$VENV/bin/python" ] || ! "$VENV/bin/python" -c "import importlib.util, sys; sys.exit(not importlib.util.find_spec('bpy'))"; then
    echo "no bpy venv at $VENV: skipped (scripts/setup.sh --test makes it; PyPI's bpy needs Python 3.11)"
    exit 77
  fi
  rm -rf "$WORK" && mkdir -p "$WORK/user_scripts"
  if [ "$KIND" = extension ]; then
    ZIP=$(bash "$SRC/scripts/make_blender_extension.sh" "$BUILD" "$WORK/extensions" "$MODEL" "$WORK/no-windows" 2>/dev/null | grep linux_x64)
    # Blender's own validator (`blender --command extension validate` runs this same script).
    "$VENV/bin/python" "$(ls "$VENV"/lib/python3*/site-packages/bpy/*/scripts/addons_core/bl_pkg/cli/blender_ext.py)" validate "$ZIP"
  else
    ZIP="$WORK/silk_blender.zip"
    bash "$SRC/scripts/make_blender_addon.sh" "$BUILD" "$ZIP" "$MODEL" >/dev/null
  fi
  # bpy is imported first (bmesh, addon_utils come with it), then the same test as in Blender.
  env -u SILK_LIBRARY BLENDER_USER_SCRIPTS="$WORK/user_scripts" BLENDER_USER_CONFIG="$WORK/config" \
    BLENDER_USER_EXTENSIONS="$WORK/extensions_user" SILK_ADDON_ZIP="$ZIP" SILK_ADDON_KIND="$KIND" \
    SILKGEN="$SILKGEN" SILK_TEST_MODEL="$MODEL" SILK_DEV_MESH="$DEV_MESH" SILK_WORK="$WORK" SILK_RENDER= \
    SILK_MESH_CHECK="$MESH_CHECK" \
    "$VENV/bin/python" -c 'import bpy, runpy, sys; sys.argv = sys.argv[1:]; runpy.run_path(sys.argv[0], run_name="__main__")' \
    "$SRC/tests/blender/test_silk_addon.py"
  exit
fi
if ! command -v blender >/dev/null; then
  echo "blender not installed: skipped (scripts/setup.sh --test installs Debian's blender)"
  exit 77
fi
if { [ "$MODE" = modal ] || [ "$MODE" = screenshot ]; } && ! command -v xvfb-run >/dev/null; then
  echo "xvfb-run not installed: skipped (scripts/setup.sh --test installs Debian's xvfb)"
  exit 77
fi
rm -rf "$WORK" && mkdir -p "$WORK/user_scripts"
bash "$SRC/scripts/make_blender_addon.sh" "$BUILD" "$WORK/silk_blender.zip" "$MODEL" >/dev/null
if [ "$MODE" = modal ]; then
  # A windowed Blender on a private X server; Mesa's software OpenGL draws it.
  RUN=(timeout 300 xvfb-run -a -s "-screen 0 1280x720x24" blender --factory-startup --enable-event-simulate
       --python "$SRC/tests/blender/test_silk_addon_modal.py")
elif [ "$MODE" = screenshot ]; then  # docs/images/blender_sidebar.png (tests/blender/screenshot_sidebar.py)
  # An empty .blend opened on the command line: Blender shows no splash screen over the picture.
  blender -b --factory-startup --python-expr "import bpy; bpy.ops.wm.save_as_mainfile(filepath='$WORK/empty.blend')" >/dev/null
  RUN=(timeout 300 xvfb-run -a -s "-screen 0 1280x720x24" blender --factory-startup --enable-event-simulate
       "$WORK/empty.blend" --python "$SRC/tests/blender/screenshot_sidebar.py")
else
  RUN=(blender -b --factory-startup --python-exit-code 1 --python "$SRC/tests/blender/test_silk_addon.py")
fi
# The add-on installs into a scratch user-scripts folder, never the user's own.
env -u SILK_LIBRARY BLENDER_USER_SCRIPTS="$WORK/user_scripts" BLENDER_USER_CONFIG="$WORK/config" \
  SILK_ADDON_ZIP="$WORK/silk_blender.zip" SILKGEN="$SILKGEN" SILK_TEST_MODEL="$MODEL" \
  SILK_DEV_MESH="$DEV_MESH" SILK_MESH_CHECK="$MESH_CHECK" SILK_MODAL_MODEL="$SRC/models/default" SILK_WORK="$WORK" SILK_RENDER="${SILK_RENDER:-$WORK/silk_blender.png}" \
  SILK_SCREENSHOT="${SILK_SCREENSHOT:-$WORK/blender_sidebar.png}" \
  "${RUN[@]}" 2>&1 | { grep -v "^Read prefs\|^Blender quit\|^Warning: .*depsgraph" || true; }
# Blender's exit status (set -e + pipefail already stop on it; the grep never fails).
exit "${PIPESTATUS[0]}"
