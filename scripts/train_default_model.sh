#!/usr/bin/env bash
# Reproduces models/default: the `micro` Mesh Silksong model trained on CPU on the 0 A.D. train
# split, exported to ONNX with its model card. Each stage can be rerun alone: STAGES="train export".
#
#   bash scripts/train_default_model.sh                 # all stages (about 1.5 h on 2 CPU cores)
#   SILK_DATA_DIR=/data STAGES="train" bash scripts/train_default_model.sh
#
# Training resumes from $RUN/checkpoint.pt when interrupted; delete $RUN to start over.
set -euo pipefail
cd "$(dirname "$0")/.."

DATA_DIR=${SILK_DATA_DIR:-/tmp/silk-data}
INDEX_DIR=${INDEX_DIR:-$DATA_DIR/index/0ad}
RUN=${RUN:-$DATA_DIR/runs/micro-default}
OUT=${OUT:-models/default}
THREADS=${THREADS:-1}
STAGES=${STAGES:-"build fetch install dataset train export eval bench card"}
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

if has train; then
  silk-export train --index "$INDEX_DIR/index.jsonl" --root "$DATA_DIR/0ad" --out "$RUN" \
    --config micro --steps 800 --batch-size 4 --lr 1e-3 --lr-min 1e-4 --warmup 50 --seed 0 \
    --threads "$THREADS" --log-every 5 --val-every 100 --val-meshes 16 --ckpt-minutes 4 --max-minutes 75
fi

if has export; then
  silk-export export --checkpoint "$RUN/checkpoint.pt" --out "$OUT" \
    --data "0 A.D. art meshes (0ad-data 0.0.26, CC BY-SA 3.0), train split, dev corpus excluded"
  cp "$RUN/loss.png" "$OUT/loss.png"
fi

if has eval; then
  for split in val test dev; do
    silk-export loss --checkpoint "$RUN/checkpoint.pt" --index "$INDEX_DIR/index.jsonl" --root "$DATA_DIR/0ad" \
      --split "$split" --out "$RUN/eval/loss_$split.json"
  done
  # 16 meshes per split, evenly spaced by token count (<= 2,046 tokens). First the shipped ONNX
  # model through the C++ runtime (silkgen: grammar-constrained, fp32, 1 thread) ...
  SILKGEN=${SILKGEN:-build/apps/silkgen}
  if [ -x "$SILKGEN" ]; then
    for split in test dev; do
      silk-export generate --runtime "$SILKGEN" --model "$OUT" --out "$RUN/eval/$split" --seed 0 \
        --index "$INDEX_DIR/index.jsonl" --root "$DATA_DIR/0ad" --split "$split" --limit 16
      silk-export eval "$RUN/eval/$split/generated" "$RUN/eval/$split/reference" --out "$RUN/eval/$split.json"
    done
  fi
  # ... then the PyTorch checkpoint without a grammar mask (how often is raw sampling legal?).
  silk-export generate --model "$RUN/checkpoint.pt" --out "$RUN/eval/torch_test" --seed 0 \
    --index "$INDEX_DIR/index.jsonl" --root "$DATA_DIR/0ad" --split test --limit 16
  silk-export eval "$RUN/eval/torch_test/generated" "$RUN/eval/torch_test/reference" \
    --out "$RUN/eval/torch_test.json"
fi

# Training throughput of every config on this machine (synthetic 1,024-token sequences).
has bench && silk-export bench --configs micro tiny small paper --steps 2 --seq-len 1024 --threads "$THREADS" \
  --out "$RUN/bench.json"

has card && silk-export card --model-dir "$OUT" --run-dir "$RUN" --bench-json "$RUN/bench.json"
echo "train_default_model: done -> $OUT"
