#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Renders Silk's inputs beside its outputs headless in Blender (scripts/render_pairs.py), so the
# pictures in the README and docs can be made again by anyone after a model or sampling change.
#
#   bash scripts/render_pictures.sh demo [PNG]        # samples/torus_knot.obj beside out/torus_knot.glb
#                                                     # (scripts/demo.sh makes it); default out/torus_knot.png
#   bash scripts/render_pictures.sh grid DIR [PNG]    # DIR from `silk-export generate`: reference/<name>.obj
#                                                     # beside generated/<name>.obj, 4 per row, each side
#                                                     # fitted to the cell (references are normalised); default DIR/grid.png
# Needs Debian's blender (scripts/setup.sh --test installs it); prints a note and exits 0 without it.
set -euo pipefail
cd "$(dirname "$0")/.."
if ! command -v blender >/dev/null 2>&1; then
  echo "render_pictures: blender not found (scripts/setup.sh --test installs it); no picture rendered"
  exit 0
fi
render() {  # args for render_pairs.py
  local log
  log=$(mktemp)
  if ! blender -b --factory-startup --python-exit-code 1 --python scripts/render_pairs.py -- "$@" >"$log" 2>&1; then
    cat "$log" >&2
    rm -f "$log"
    echo "render_pictures: blender failed" >&2
    exit 1
  fi
  grep '^render_pairs:' "$log" || true
  rm -f "$log"
}
mode=${1:-demo}
case "$mode" in
  demo)
    png=${2:-out/torus_knot.png}
    [ -f out/torus_knot.glb ] || { echo "render_pictures: out/torus_knot.glb missing (run scripts/demo.sh)" >&2; exit 1; }
    mkdir -p "$(dirname "$png")"
    render --out "$png" --size 1280x640 --pair samples/torus_knot.obj out/torus_knot.glb
    ;;
  grid)
    dir=${2:?usage: render_pictures.sh grid DIR [PNG]}
    png=${3:-$dir/grid.png}
    pairs=()
    for g in "$dir"/generated/*.obj; do
      [ -e "$g" ] || continue
      r="$dir/reference/$(basename "$g")"
      [ -f "$r" ] && pairs+=(--pair "$r" "$g")
    done
    [ ${#pairs[@]} -gt 0 ] || { echo "render_pictures: no generated/reference pairs under $dir" >&2; exit 1; }
    mkdir -p "$(dirname "$png")"
    render --out "$png" --cols 4 --fit-each --size 1920x$(( (${#pairs[@]} / 3 + 3) / 4 * 480 )) "${pairs[@]}"
    ;;
  *)
    echo "usage: render_pictures.sh demo [PNG] | grid DIR [PNG]" >&2
    exit 2
    ;;
esac
