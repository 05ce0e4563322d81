// SPDX-License-Identifier: MIT
// CandidateRows: best of N's candidates decoded as rows, up to R at once with one decoder call per
// step for all (RowsDecoder over a RowsKvCache: every weight read once per call), each row with its
// own grammar, sampler chain, seed, forced runs and guides (a Generator in rows mode), so each
// candidate's ids are exactly those it gets alone. The encoder runs once for all; a candidate that
// ends leaves its row to the next one. GenerationSession scores the ended candidates in order.
#pragma once
#include <cstdint>
#include <functional>
#include <memory>
#include <utility>
#include <vector>

#include "core/cancel_check.h"
#include "core/status.h"
#include "runtime/generator.h"
#include "runtime/rows_decoder.h"
#include "runtime/rows_kv_cache.h"

namespace silk {

class CandidateRows {
 public:
  explicit CandidateRows(const Model& model);
  ~CandidateRows();

  // Runs the encoder on `points` once, then starts candidates 0 .. min(rows, N) - 1 (N =
  // options.candidates; candidate i runs with seed CandidateSeed(options.sampling.seed, i) and the
  // callbacks `callbacks(i)` gives; options.sampling.seed is candidate 0's).
  Status Start(const std::vector<float>& points, const GenerateOptions& options, int32_t rows,
               const std::function<GenerateCallbacks(int32_t)>& callbacks, const CancelCheck& cancel);
  // Up to max_ids ids over all rows (forced and sampled alike); `until_layer`: also stops after a
  // row closes a layer or a candidate ends. An ended candidate's mesh is built (`finishing` polled
  // while it is oriented) and it waits in TakeEnded; a free row takes the next candidate.
  Status Advance(int32_t max_ids, bool until_layer, const CancelCheck& finishing);
  // The candidates ended since the last call, as (index, result), in the order they ended.
  std::vector<std::pair<int32_t, GenerateResult>> TakeEnded();
  // Ends every candidate in progress now (Generator::Finish cancels it) into TakeEnded.
  Status EndLive(const CancelCheck& finishing);
  void Abandon();
  // Thread-safe, any time: stops the encoder run in progress.
  void InterruptEncoder();

  bool done() const { return live_ == 0 && next_ >= candidates_; }
  int32_t rows() const { return static_cast<int32_t>(rows_.size()); }
  int32_t started() const { return next_; }
  // The candidate in progress with the most ids (what a preview shows), or null / -1.
  const Generator* lead() const;
  // The candidates in progress: (index, its generator), by row.
  std::vector<std::pair<int32_t, const Generator*>> live() const;
  int32_t lead_candidate() const;
  int64_t cache_bytes() const { return cache_.bytes(); }
  int64_t decoder_calls() const { return decoder_ ? decoder_->calls() : 0; }          // decoder.onnx runs, all rows
  int64_t decoder_positions() const { return decoder_ ? decoder_->positions() : 0; }  // computed, padding included
  double decoder_seconds() const { return decoder_seconds_; }  // the feeds' wall time, all rows together

 private:
  struct Row {
    std::unique_ptr<Generator> generator;
    int32_t candidate = -1;
    std::vector<float> logits;  // its next logits, kept when the id budget ran out after a call
    bool ready = false;
  };
  Status StartNext(int32_t slot);
  // Steps every row's ids that need no logits (and kept logits) while the budget lasts.
  Status StepWithoutLogits(int32_t max_ids, bool until_layer, int32_t* ids, bool* stop);
  // Ends the finished rows (built, into ended_), compacting the rows to slots 0..live-1, and gives
  // the freed rows to the next candidates.
  Status Retire(const CancelCheck& finishing);
  // One RowsDecoder feed for every row waiting for logits (FeedWidth ids of each); a row whose
  // pending ids are all fed takes its id while the budget lasts.
  Status Decode(int32_t max_ids, int32_t* ids);
  int64_t FeedWidth() const;
  bool AllWaiting() const;

  const Model& model_;
  std::unique_ptr<Ort::RunOptions> encoder_run_;
  RowsKvCache cache_;
  std::unique_ptr<RowsDecoder> decoder_;
  std::vector<Row> rows_;  // slots 0..live_-1 in progress
  std::vector<float> points_;
  GenerateOptions options_;
  std::function<GenerateCallbacks(int32_t)> callbacks_;
  std::vector<std::pair<int32_t, GenerateResult>> ended_;
  double encoder_seconds_ = 0, decoder_seconds_ = 0;
  int32_t live_ = 0, next_ = 0, candidates_ = 0;
};

}  // namespace silk
