# SPDX-License-Identifier: MIT
# The shared material folder (spec/, corpus/, tools/): the one rule of every script, sourced.
# The same rule is written once per language: export/silk_export/paths.py (Python),
# cmake/SilkSharedDir.cmake (CMake; the C++ tests get its result, tests/support/test_paths.cpp).
#   1. $SILK_SHARED_DIR when set (it must be a folder);
#   2. else ../shared beside this checkout, when it holds spec/;
#   3. else ../shared beside the checkout this one was cloned from (git's remote.origin.url, a
#      local folder: `git clone . /tmp/x` leaves the material behind), when it holds spec/;
#   4. else an error naming the places looked in.
# Usage: source scripts/shared_dir.sh; shared=$(silk_shared_dir) || exit 2   (prints the absolute path)
silk_shared_dir() {
  local repo origin candidate
  repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
  if [ -n "${SILK_SHARED_DIR:-}" ]; then
    if [ -d "$SILK_SHARED_DIR" ]; then
      (cd "$SILK_SHARED_DIR" && pwd)
      return 0
    fi
    echo "no shared material: SILK_SHARED_DIR=$SILK_SHARED_DIR is not a folder" >&2
    return 1
  fi
  origin=$(git -C "$repo" config --get remote.origin.url 2>/dev/null || true)
  for candidate in "$repo/../shared" ${origin:+"$origin/../shared"}; do
    if [ -d "$candidate/spec" ]; then
      (cd "$candidate" && pwd)
      return 0
    fi
  done
  echo "no shared material (spec/, corpus/): SILK_SHARED_DIR is not set and neither $repo/../shared${origin:+ nor $origin/../shared} holds spec/; set SILK_SHARED_DIR to the folder that does" >&2
  return 1
}
