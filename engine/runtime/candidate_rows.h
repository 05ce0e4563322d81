// SPDX-License-Identifier: MIT
// CandidateRows: best of N's candidates decoded as rows, up to R at once with one decoder call per
// step for all (RowsDecoder over a RowsKvCache: every weight read once per call), each row with its
// own grammar, sampler chain, seed, forced runs and guides (a Generator in rows mode), so each
// candidate's ids are exactly those it gets alone. The encoder runs once per mesh; a candidate that
// ends leaves its row to the next one. GenerationSession scores the ended candidates in order.
// Rows may come from several meshes at once (Open + AddMesh, MeshRows: a batch of inputs): each
// mesh has its own points, options and encoder output (one of the decoder's sources), and a free
// row takes the next candidate of the first mesh, in the order added, that has one to start.
#pragma once
#include <cstdint>
#include <functional>
#include <map>
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

  // One mesh: runs the encoder on `points` once, then starts candidates 0 .. min(rows, N) - 1 (N =
  // options.candidates; candidate i runs with seed CandidateSeed(options.sampling.seed, i) and the
  // callbacks `callbacks(i)` gives; options.sampling.seed is candidate 0's).
  Status Start(const std::vector<float>& points, const GenerateOptions& options, int32_t rows,
               const std::function<GenerateCallbacks(int32_t)>& callbacks, const CancelCheck& cancel);
  // Many meshes: `rows` rows over at most `sources` meshes in flight (AddMesh); nothing runs yet.
  // A row's error other than a cancel fails its mesh alone (TakeEndedRows: an entry with the error).
  Status Open(int32_t rows, int32_t sources);
  // Runs the encoder on `points` (polling `cancel`) and queues the mesh's options.candidates
  // candidates (at most min(options.rows, candidates) of them in rows at once); needs a free source
  // (free_sources() > 0). Returns the mesh's id (0, 1, ... in the order added since Open).
  StatusOr<int32_t> AddMesh(const std::vector<float>& points, const GenerateOptions& options,
                            const std::function<GenerateCallbacks(int32_t)>& callbacks, const CancelCheck& cancel);
  int32_t free_sources() const { return static_cast<int32_t>(free_sources_.size()); }
  // Up to max_ids ids over all rows (forced and sampled alike); `until_layer`: also stops after a
  // row closes a layer or a candidate ends; always stops once a mesh has ended all its candidates. An ended candidate's
  // mesh is built (`finishing` polled while it is oriented) and it waits in TakeEnded; a free row takes the next
  // candidate.
  Status Advance(int32_t max_ids, bool until_layer, const CancelCheck& finishing);
  // The candidates ended since the last call, as (index, result), in the order they ended.
  std::vector<std::pair<int32_t, GenerateResult>> TakeEnded();
  struct Ended {
    int32_t mesh = 0, candidate = 0;
    Status status;  // not ok: the mesh failed (once, candidate -1; its other rows were dropped)
    GenerateResult result;
    bool last = false;  // the mesh's last entry: it has no candidate left
  };
  // The same with the mesh of each (many meshes).
  std::vector<Ended> TakeEndedRows();
  // Ends every candidate in progress now (Generator::Finish cancels it) into TakeEnded.
  Status EndLive(const CancelCheck& finishing);
  void Abandon();
  // Thread-safe, any time: stops the encoder run in progress.
  void InterruptEncoder();

  bool done() const { return live_ == 0 && meshes_.empty(); }
  int32_t rows() const { return static_cast<int32_t>(rows_.size()); }
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
  struct Mesh {
    std::vector<float> points;
    GenerateOptions options;
    std::function<GenerateCallbacks(int32_t)> callbacks;
    double encoder_seconds = 0;
    int32_t source = 0, next = 0, live = 0, cap = 1;
    bool failed = false;
  };
  struct Row {
    std::unique_ptr<Generator> generator;
    int32_t mesh = -1, candidate = -1;
    bool failed = false;        // its mesh failed: dropped by Retire
    std::vector<float> logits;  // its next logits, kept when the id budget ran out after a call
    bool ready = false;
  };
  // The first mesh with a candidate to start and room in its rows, or -1.
  int32_t NextMesh() const;
  Status StartNext(int32_t slot, int32_t mesh);
  // A row's step status: a failure other than a cancel fails its mesh alone when isolating (many
  // meshes); otherwise it is returned.
  Status Check(int32_t slot, Status status);
  // Row `slot` leaves: the last live row moves into it.
  void Vacate(int32_t slot);
  int32_t SourceOf(int32_t slot) const;
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
  std::vector<Row> rows_;           // slots 0..live_-1 in progress
  std::map<int32_t, Mesh> meshes_;  // in flight, by id (the order added)
  std::vector<int32_t> free_sources_;
  std::vector<Ended> ended_;
  double decoder_seconds_ = 0;
  int32_t live_ = 0, next_mesh_ = 0;
  bool isolate_ = false, mesh_ended_ = false;
};

}  // namespace silk
