#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# ctest's format check: scripts/format.sh --check on the source tree ($1, default: this checkout),
# skipped (77) where the pinned formatters are missing, so a machine without them is not failed.
set -uo pipefail
ROOT=${1:-"$(cd "$(dirname "$0")/../.." && pwd)"}
bash "$ROOT/scripts/format.sh" --check
rc=$?
[ $rc = 3 ] && { echo "check_format: the pinned formatters are not installed: skipped"; exit 77; }
exit $rc
