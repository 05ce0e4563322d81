#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Quality of what silkgen writes, on meshes the model never trained on: a fixed sample of the
# 0 A.D. test split (40 meshes evenly spaced by token count, from the dataset index) and the 160
# dev meshes. Prints one table row per set: mean CD, HD, NC, |NC| (`silk-export eval`), the share
# of outputs that pass the independent checker (../shared/tools/mesh_check.py), faces and
# seconds per mesh. Extra arguments go to silkgen, so settings can be compared row by row:
#
#   bash scripts/eval_quality.sh OUT_DIR [silkgen options ...]
#   bash scripts/eval_quality.sh /tmp/q/a --model models/default
#   SETS="dev" LIMIT_TEST=40 THREADS=2 bash scripts/eval_quality.sh /tmp/q/b --surface-tolerance 2
#   SETS="dev" LIMIT_DEV=10 bash scripts/eval_quality.sh /tmp/q/c --face-guidance hard   # a tuning subset
#
# Needs the build (silkgen), silk-export on the PATH and, for the test split, the index made by
# `silk-export dataset` (scripts/train_default_model.sh, stages fetch + dataset).
set -euo pipefail
cd "$(dirname "$0")/.."
out=${1:?usage: eval_quality.sh OUT_DIR [silkgen options ...]}
shift
source scripts/shared_dir.sh
shared=$(silk_shared_dir) || exit 2
data=${SILK_DATA_DIR:-/tmp/silk-data}
index=${INDEX:-$data/index/0ad/index.jsonl}
silkgen=${BUILD_DIR:-build}/apps/silkgen
sets=${SETS:-"test dev"}
threads=${THREADS:-2}
export SILK_LIBRARY=${SILK_LIBRARY:-$PWD/${BUILD_DIR:-build}/engine/libsilk.so}
[ -x "$silkgen" ] || { echo "eval_quality: $silkgen not built (scripts/build.sh)" >&2; exit 1; }

inputs() {  # set -> one input path per line
  case "$1" in
    dev)  # LIMIT_DEV=n: n meshes evenly spaced through the sorted list (tuning subsets); default all 160
      ls "$shared"/corpus/dev/*.obj | awk -v n="${LIMIT_DEV:-0}" '{a[NR]=$0} END {
        if (n <= 0 || n >= NR) { for (i = 1; i <= NR; i++) print a[i]; exit }
        for (i = 0; i < n; i++) print a[int(i * NR / n) + 1] }' ;;
    test)
      [ -f "$index" ] || { echo "eval_quality: no index at $index (silk-export dataset)" >&2; return 1; }
      python3 - "$index" "$data/0ad" "${LIMIT_TEST:-40}" <<'PY'
import sys
from pathlib import Path
from silk_export.evaluation.generate import pick_from_index
for p in pick_from_index(Path(sys.argv[1]), Path(sys.argv[2]), "test", int(sys.argv[3]), 2046):
    print(p)
PY
      ;;
  esac
}

for set in $sets; do
  dir="$out/$set"
  mkdir -p "$dir/generated" "$dir/reference" "$dir/stats"
  inputs "$set" >"$dir/inputs.txt"
  while read -r f; do
    name=$(basename "$f"); name=${name%%.*}
    ln -sf "$(realpath "$f")" "$dir/reference/$name.${f##*.}"
    "$silkgen" "$f" -o "$dir/generated/$name.obj" --threads "$threads" --stats "$dir/stats/$name.json" "$@" \
      >/dev/null 2>"$dir/stats/$name.err" || echo "eval_quality: $name: silkgen failed ($(tail -1 "$dir/stats/$name.err"))" >&2
  done <"$dir/inputs.txt"
  silk-export eval "$dir/generated" "$dir/reference" --out "$dir/eval.json" >/dev/null
  python3 "$shared/tools/mesh_check.py" "$dir"/generated/*.obj >"$dir/mesh_check.txt" 2>&1 || true
  python3 - "$dir" "$set" "$*" <<'PY'
import glob, json, sys
d, name, opts = sys.argv[1], sys.argv[2], sys.argv[3]
inputs = [l for l in open(f"{d}/inputs.txt").read().split("\n") if l]
summ = json.load(open(f"{d}/eval.json"))["summary"]
stats = [json.load(open(f)) for f in sorted(glob.glob(f"{d}/stats/*.json"))]
last = open(f"{d}/mesh_check.txt").read().strip().split("\n")[-1]  # "N passed, M failed"
passed = int(last.split()[0]) if last.endswith("failed") else 0  # missing outputs count as failures
faces = sum(s.get("faces", 0) for s in stats) / max(len(inputs), 1)
secs = sum(s["seconds"]["total"] for s in stats) / max(len(stats), 1)
row = {"set": name, "options": opts, "meshes": len(inputs), "outputs": len(stats),
       "mean_cd": summ.get("mean_cd"), "mean_hd": summ.get("mean_hd"), "mean_nc": summ.get("mean_nc"),
       "mean_abs_nc": summ.get("mean_abs_nc"), "mesh_check_pass": passed, "faces_per_mesh": faces,
       "seconds_per_mesh": secs}
json.dump(row, open(f"{d}/row.json", "w"), indent=1, allow_nan=False)  # valid JSON or an error
f = lambda v: "n/a" if v is None else f"{v:.3f}"
print(f"| {name} | {opts or 'defaults'} | {len(inputs)} | {f(row['mean_cd'])} | {f(row['mean_hd'])} | "
      f"{f(row['mean_nc'])} | {f(row['mean_abs_nc'])} | {passed}/{len(inputs)} | {faces:.0f} | {secs:.2f} |")
PY
done
