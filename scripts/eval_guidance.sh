#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Measures the sampling defaults of a model folder (MODEL, default models/default): surface
# guidance, best of N and temperature (the defaults of silk_generate_params.surface_tolerance /
# .candidates and the bundled model's model.json "sampling" were chosen from its tables,
# docs/runtime.md, models/training/README.md): 40 meshes of the 0 A.D. validation split when
# its index exists, else the first 40 dev-corpus meshes (LIMIT=N: fewer); seed 0, 1 thread,
# MAX_TOKENS-token cap (default 512; 0 = the model's length); `silk-export eval` with 2,000
# surface points per mesh (POINTS=...) on each run. A run whose generate.json exists is only
# re-evaluated. Rows: each tolerance (candidates 1), then each N at BEST_TOLERANCE, then each
# of TEMPERATURES (default none: the model's own) at BEST_TOLERANCE with candidates 1
# (BEST_TEMPERATURE=T runs the N rows at T, N = 1 included).
# Usage: SILK_LIBRARY=build/engine/libsilk.so scripts/eval_guidance.sh [OUT_DIR=out/guidance] [TOLERANCES="0 1 2 3 4"] [CANDIDATES="1 2 4 8"] [BEST_TOLERANCE=2]
#        MODEL=/tmp/m TEMPERATURES="0.5 1.0 1.3" MAX_TOKENS=0 scripts/eval_guidance.sh /tmp/g "" "" 2
set -euo pipefail
cd "$(dirname "$0")/.."
out="${1:-out/guidance}"; tolerances="${2-0 1 2 3 4}"; candidates="${3-1 2 4 8}"; best="${4-2}"
source scripts/shared_dir.sh
shared=$(silk_shared_dir) || exit 2
index="${SILK_DATA_DIR:-/tmp/silk-data}/index/0ad/index.jsonl"
if [ -f "$index" ]; then
  inputs=(--index "$index" --split val --limit "${LIMIT:-40}")
else
  mapfile -t files < <(ls "$shared"/corpus/dev/*.obj | head -"${LIMIT:-40}")
  inputs=("${files[@]}")
fi
silk_export() { PYTHONPATH="$PWD/export${PYTHONPATH:+:$PYTHONPATH}" python3 -m silk_export "$@"; }  # this checkout's
model="${MODEL:-models/default}"
run() {  # name tolerance candidates [temperature]
  local dir="$out/$1" temp=()
  [ -n "${4:-}" ] && temp=(--temperature "$4")
  [ -f "$dir/generate.json" ] ||
    silk_export generate --model "$model" --out "$dir" --seed 0 --threads 1 --max-tokens "${MAX_TOKENS:-512}" \
      --surface-tolerance "$2" --candidates "$3" "${temp[@]}" "${inputs[@]}" >/dev/null 2>"$dir.log" || { cat "$dir.log"; exit 1; }
  silk_export eval "$dir/generated" "$dir/reference" --points "${POINTS:-2000}" --out "$dir/eval.json" >/dev/null
  python3 - "$dir" "$2" "$3" <<'PY'
import json, sys
d, t, n = sys.argv[1:]
g = json.load(open(f"{d}/generate.json")); e = json.load(open(f"{d}/eval.json"))["summary"]
rows = g["meshes"]; sec = sum(r.get("seconds", 0) for r in rows) / len(rows)
fb = sum(r.get("guidance_fallbacks", 0) for r in rows); gt = sum(r.get("guided_tokens", 0) for r in rows)
m = lambda k: float("nan") if e.get(k) is None else e[k]  # absent, or null (a non-finite mean)
print(f"| {g.get('settings', {}).get('temperature', '?')} | {t} | {n} | {g['decoded_with_faces']}/{len(rows)} | {m('mean_cd'):.4f} | "
      f"{m('mean_hd'):.4f} | {m('mean_nc'):.4f} | {m('mean_abs_nc'):.4f} | "
      f"{e.get('mean_faces', 0):.0f} | {sec:.2f} | {fb}/{gt} |")
PY
}
mkdir -p "$out"
echo "| temperature | tolerance | candidates | with faces | CD | HD | NC | abs NC | faces | s/mesh | fallbacks/guided |"
echo "|---|---|---|---|---|---|---|---|---|---|---|"
for t in $tolerances; do run "t${t}_n1" "$t" 1; done
# BEST_TEMPERATURE=T: the candidates rows at that temperature (default: the model's own).
bt="${BEST_TEMPERATURE:-}"
for n in $candidates; do [ "$n" = 1 ] && [ -z "$bt" ] || run "${bt:+T${bt}_}t${best}_n${n}" "$best" "$n" "$bt"; done
for T in ${TEMPERATURES:-}; do run "T${T}_t${best}_n1" "$best" 1 "$T"; done
