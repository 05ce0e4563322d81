#!/usr/bin/env bash
# ctest blender_addon: builds the add-on zip (bundled model = the tiny test model) and runs the
# headless Blender test against it. Exit 77 (ctest: skipped) where Blender is not installed.
# Usage: run_blender_test.sh BUILD_DIR SOURCE_DIR WORK_DIR SILKGEN DEV_MESH
set -euo pipefail
BUILD=$1 SRC=$2 WORK=$3 SILKGEN=$4 DEV_MESH=$5
if ! command -v blender >/dev/null; then
  echo "blender not installed: skipped (scripts/setup.sh installs Debian's blender)"
  exit 77
fi
rm -rf "$WORK" && mkdir -p "$WORK/user_scripts"
MODEL=${SILK_ADDON_MODEL:-$SRC/tests/models/tiny}  # the docs picture uses models/default
bash "$SRC/scripts/make_blender_addon.sh" "$BUILD" "$WORK/silk_blender.zip" "$MODEL" >/dev/null
# The add-on installs into a scratch user-scripts folder, never the user's own.
env -u SILK_LIBRARY BLENDER_USER_SCRIPTS="$WORK/user_scripts" BLENDER_USER_CONFIG="$WORK/config" \
  SILK_ADDON_ZIP="$WORK/silk_blender.zip" SILKGEN="$SILKGEN" SILK_TEST_MODEL="$MODEL" \
  SILK_DEV_MESH="$DEV_MESH" SILK_WORK="$WORK" SILK_RENDER="${SILK_RENDER:-$WORK/silk_blender.png}" \
  blender -b --factory-startup --python-exit-code 1 --python "$SRC/tests/blender/test_silk_addon.py" 2>&1 |
  grep -v "^Read prefs\|^Blender quit\|^Warning: .*depsgraph" || true
test "${PIPESTATUS[0]}" -eq 0
