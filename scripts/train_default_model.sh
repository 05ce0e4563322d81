#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# Trains the bundled model (models/default) on CPU on the 0 A.D. train split and exports it to
# ONNX with its model card: the configuration the sweep chose (CONFIG, nano: the model in
# models/default, 60.2 M tokens, finished 2026-12-03). Each stage can be rerun alone:
# STAGES="train export"; the bundled model's export: TEMPERATURE=1.6 CANDIDATES=8.
#
#   bash scripts/train_default_model.sh                        # all stages
#   MINUTES=90 STAGES="restore train pack" bash scripts/train_default_model.sh   # one slice of training
#   SILK_DATA_DIR=/data STAGES="train" bash scripts/train_default_model.sh
#
# Training spans sessions: `restore` copies the repository's resumable checkpoint
# (models/training/checkpoint.pt, with its log) into $RUN when $RUN has none, `train` resumes
# from $RUN/checkpoint.pt for at most MINUTES (0 = to the end), and `pack` writes the checkpoint
# back into the repository in its packed form (optimizer moments in bf16, <= 40 MB; replaced in
# place, never accumulated) with the training log. Delete $RUN and models/training to start over.
set -euo pipefail
cd "$(dirname "$0")/.."

DATA_DIR=${SILK_DATA_DIR:-/tmp/silk-data}
INDEX_DIR=${INDEX_DIR:-$DATA_DIR/index/0ad}
# nano: the lowest held-out loss at equal CPU time of the sweep below (models/training/README.md).
CONFIG=${CONFIG:-nano}
RUN=${RUN:-$DATA_DIR/runs/$CONFIG-default}
OUT=${OUT:-models/default}
REPO_TRAIN=${REPO_TRAIN:-models/training}
THREADS=${THREADS:-2}    # torch threads: both cores of the reference machine
WORKERS=${WORKERS:-1}    # DataLoader processes tokenising through libsilk beside the optimizer
# 17,000 steps x 4 sequences x ~887 tokens (the mean of the first run) = ~60 M tokens.
STEPS=${STEPS:-17000}
MINUTES=${MINUTES:-0}
STAGES=${STAGES:-"build fetch install dataset restore train pack export eval bench card"}
# Stage `sweep` (not in the default list): the candidate configurations trained for the same CPU
# time from scratch, then scored on the whole val split; the lowest held-out loss is the one to
# train (CONFIG). Slow: SWEEP_CPU_MINUTES of CPU per configuration.
SWEEP_CONFIGS=${SWEEP_CONFIGS:-"nano micro mini"}
SWEEP_CPU_MINUTES=${SWEEP_CPU_MINUTES:-12}
mkdir -p "$RUN/eval"
export SILK_DATA_DIR=$DATA_DIR
export SILK_LIBRARY=${SILK_LIBRARY:-$PWD/build/engine/libsilk.so}

has() { [[ " $STAGES " == *" $1 "* ]]; }

if has build; then
  cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
  cmake --build build --target silk silktok
  cmake --build build --target silkgen 2>/dev/null || echo "no silkgen (no onnxruntime): runtime eval skipped"
fi
has fetch && bash scripts/fetch_0ad.sh
has install && python3 -m pip install -q -e export
has dataset && silk-export dataset --root "$DATA_DIR/0ad" --out "$INDEX_DIR"

if has sweep; then
  for c in $SWEEP_CONFIGS; do
    run="$DATA_DIR/runs/sweep-$c"
    # A finished sweep run is kept (rerunning would train it SWEEP_CPU_MINUTES more): delete the
    # folder to measure it again.
    [ -f "$run/loss_val.json" ] && { echo "sweep: $c already measured ($run)"; continue; }
    silk-export train --index "$INDEX_DIR/index.jsonl" --root "$DATA_DIR/0ad" --out "$run" \
      --config "$c" --steps "$STEPS" --batch-size 4 --lr 1e-3 --lr-min 1e-4 --warmup 200 --seed 0 \
      --threads "$THREADS" --workers 0 --log-every 20 --val-every 0 --no-progress \
      --max-cpu-minutes "$SWEEP_CPU_MINUTES" >"$run.log" 2>&1
    silk-export loss --checkpoint "$run/checkpoint.pt" --index "$INDEX_DIR/index.jsonl" --root "$DATA_DIR/0ad" \
      --split val --out "$run/loss_val.json" --threads "$THREADS" >/dev/null
  done
  python3 - "$DATA_DIR/runs" $SWEEP_CONFIGS <<'PY' | tee "$RUN/sweep.md"
import json, sys, torch
from pathlib import Path
runs = Path(sys.argv[1])
print("| config | parameters | CPU minutes | steps | tokens | val loss (nats/token) |")
print("|---|---|---|---|---|---|")
for c in sys.argv[2:]:
    d = runs / f"sweep-{c}"
    ck = torch.load(d / "checkpoint.pt", map_location="cpu", weights_only=False)
    log = [json.loads(l) for l in open(d / "log.jsonl")]
    tokens = sum(r.get("tokens", 0) for r in log if r.get("kind") == "train")
    loss = json.load(open(d / "loss_val.json"))
    params = sum(v.numel() for v in ck["model"].values())
    print(f"| {c} | {params:,} | {ck['args'].get('max_cpu_minutes')} | {ck['step']} | {tokens:,} | "
          f"{loss.get('nats_per_token', loss.get('loss'))} |")
PY
fi

if has restore && [ ! -f "$RUN/checkpoint.pt" ] && [ -f "$REPO_TRAIN/checkpoint.pt" ]; then
  echo "train_default_model: resuming from $REPO_TRAIN/checkpoint.pt"
  cp "$REPO_TRAIN/checkpoint.pt" "$RUN/checkpoint.pt"
  [ -f "$REPO_TRAIN/log.jsonl" ] && cp "$REPO_TRAIN/log.jsonl" "$RUN/log.jsonl"
fi

# Stage `seed` (not in the default list): a run with no checkpoint here or in the repository
# starts from the sweep's run of CONFIG, which used the same seed, schedule and sample stream, so
# the sweep's steps count toward the run.
if has seed && [ ! -f "$RUN/checkpoint.pt" ] && [ -f "$DATA_DIR/runs/sweep-$CONFIG/checkpoint.pt" ]; then
  echo "train_default_model: starting from the sweep's $CONFIG run"
  cp "$DATA_DIR/runs/sweep-$CONFIG/checkpoint.pt" "$DATA_DIR/runs/sweep-$CONFIG/log.jsonl" "$RUN/"
fi

if has train; then
  silk-export train --index "$INDEX_DIR/index.jsonl" --root "$DATA_DIR/0ad" --out "$RUN" \
    --config "$CONFIG" --steps "$STEPS" --batch-size 4 --lr 1e-3 --lr-min 1e-4 --warmup 200 --seed 0 \
    --threads "$THREADS" --workers "$WORKERS" --log-every 20 --val-every 500 --val-meshes 16 \
    --ckpt-minutes 10 --max-minutes "$MINUTES"
fi

if has pack; then
  mkdir -p "$REPO_TRAIN"
  silk-export pack-checkpoint "$RUN/checkpoint.pt" -o "$REPO_TRAIN/checkpoint.pt"
  for f in log.jsonl loss.png run.json; do
    [ -f "$RUN/$f" ] && cp "$RUN/$f" "$REPO_TRAIN/$f"
  done
fi

if has export; then
  # TEMPERATURE, TOP_K and CANDIDATES: the model's default sampling and best of N, chosen on the
  # val split with scripts/eval_guidance.sh; written into model.json, which silkgen and the C API read.
  # KV_VARIANTS / KV_PRECISION: the contract v4 cache variants shipped and the default cache. The
  # bundled folder ships the fp16 ones only (40 MB limit) and uses them by default, so best of N
  # runs its candidates as rows of one decoder call (docs/runtime.md, "Rows").
  silk-export export --checkpoint "$RUN/checkpoint.pt" --out "$OUT" \
    ${TEMPERATURE:+--temperature "$TEMPERATURE"} ${TOP_K:+--top-k "$TOP_K"} \
    ${CANDIDATES:+--candidates "$CANDIDATES"} \
    --kv-variants ${KV_VARIANTS:-fp16} --kv-precision "${KV_PRECISION:-fp16}" \
    --data "0 A.D. art meshes (0ad-data 0.0.26, CC BY-SA 3.0), train split, dev corpus excluded"
  cp "$RUN/loss.png" "$OUT/loss.png"
fi

if has eval; then
  for split in val test dev; do
    silk-export loss --checkpoint "$RUN/checkpoint.pt" --index "$INDEX_DIR/index.jsonl" --root "$DATA_DIR/0ad" \
      --split "$split" --out "$RUN/eval/loss_$split.json"
  done
  # 16 meshes per split, evenly spaced by token count (<= 2,046 tokens): the shipped ONNX model
  # through libsilk's runtime (grammar-constrained, fp32, 1 thread), as silkgen runs it.
  for split in test dev; do
    silk-export generate --model "$OUT" --out "$RUN/eval/$split" --seed 0 \
      --index "$INDEX_DIR/index.jsonl" --root "$DATA_DIR/0ad" --split "$split" --limit 16
    silk-export eval "$RUN/eval/$split/generated" "$RUN/eval/$split/reference" --out "$RUN/eval/$split.json"
  done
fi

# Training throughput of every config on this machine (synthetic 1,024-token sequences).
has bench && silk-export bench --configs nano micro tiny small paper --steps 2 --seq-len 1024 --threads "$THREADS" \
  --out "$RUN/bench.json"

has card && silk-export card --model-dir "$OUT" --run-dir "$RUN" --bench-json "$RUN/bench.json"
echo "train_default_model: done -> $OUT"
