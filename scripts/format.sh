#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Formats the tree: C/C++ with clang-format 14 (.clang-format), Python with ruff (ruff.toml: the
# formatter, then the lint set's safe fixes). Only files git tracks; nothing else is touched.
#   scripts/format.sh           rewrite the files in place
#   scripts/format.sh --check   change nothing; fail naming every file that is not formatted and
#                               every lint finding (tests/tools/check_format.sh runs this for ctest)
# The tools are pinned (clang-format-14 from Debian bookworm; ruff in scripts/format-requirements.txt,
# both installed by scripts/setup.sh --test); $CLANG_FORMAT and $RUFF name other binaries.
set -euo pipefail
cd "$(dirname "$0")/.."
MODE=fix
case "${1:-}" in
  "") ;;
  --check) MODE=check ;;
  *) echo "usage: scripts/format.sh [--check]  (unknown argument '$1')" >&2; exit 2 ;;
esac
CLANG_FORMAT=${CLANG_FORMAT:-clang-format-14}
RUFF=${RUFF:-ruff}
RUFF_PIN=$(sed -n 's/^ruff==//p' scripts/format-requirements.txt)
command -v "$CLANG_FORMAT" >/dev/null ||
  { echo "format: $CLANG_FORMAT not found (apt-get install clang-format-14, or scripts/setup.sh --test)" >&2; exit 3; }
"$CLANG_FORMAT" --version | grep -q 'version 14\.' ||
  { echo "format: $CLANG_FORMAT is not clang-format 14: $("$CLANG_FORMAT" --version)" >&2; exit 3; }
command -v "$RUFF" >/dev/null ||
  { echo "format: $RUFF not found (pip install -r scripts/format-requirements.txt)" >&2; exit 3; }
[ "$("$RUFF" --version)" = "ruff $RUFF_PIN" ] ||
  { echo "format: $("$RUFF" --version), scripts/format-requirements.txt pins ruff $RUFF_PIN" >&2; exit 3; }

mapfile -d '' CXX < <(git ls-files -z -- '*.c' '*.cc' '*.cpp' '*.h' '*.hpp')
mapfile -d '' PY < <(git ls-files -z -- '*.py')
status=0
if [ "$MODE" = check ]; then
  unformatted=$(printf '%s\0' "${CXX[@]}" | xargs -0 -n 64 "$CLANG_FORMAT" --dry-run --Werror 2>&1 |
                grep -o '^[^:]*:[0-9]*:[0-9]*: error' | cut -d: -f1 | sort -u || true)
  [ -n "$unformatted" ] && { echo "$unformatted" | sed 's/$/: not clang-formatted/'; status=1; }
  "$RUFF" format --check --output-format concise "${PY[@]}" || status=1
  "$RUFF" check --output-format concise "${PY[@]}" || status=1
  [ $status = 0 ] && echo "format: ${#CXX[@]} C/C++ and ${#PY[@]} Python files formatted, no lint finding" ||
    echo "format: run scripts/format.sh to format; lint findings that remain need a hand" >&2
  exit $status
fi
printf '%s\0' "${CXX[@]}" | xargs -0 -n 64 "$CLANG_FORMAT" -i
"$RUFF" format --quiet "${PY[@]}"
"$RUFF" check --quiet --fix "${PY[@]}" || status=1  # what no safe fix resolves is printed
echo "format: ${#CXX[@]} C/C++ and ${#PY[@]} Python files formatted"
exit $status
