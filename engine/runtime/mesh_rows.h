// SPDX-License-Identifier: MIT
// MeshRows: a batch of inputs generated as rows of one CandidateRows, up to `parallel` meshes in
// flight at once (each with its own points, options and encoder output; a freed row goes to the
// next candidate of the first mesh in input order with one to start), so a farm reads the
// decoder's weights once per step for several meshes. Each input's result (ids, mesh, chosen
// candidate, every candidate's score, stats but the times) is exactly its GenerationSession run
// with the same request; a failed input fails alone. Parallel 1, or a folder before decoder
// contract v4 (one row per call), runs the inputs one after another on a GenerationSession.
#pragma once
#include <chrono>
#include <cstdint>
#include <deque>
#include <functional>
#include <map>
#include <optional>
#include <vector>

#include "core/cancel_check.h"
#include "core/status.h"
#include "runtime/candidate_rows.h"
#include "runtime/generation_session.h"
#include "runtime/input_generation.h"

namespace silk {

// An input that ended: its index (Add's) and its result or error.
struct MeshRowsEnded {
  int32_t index = 0;
  StatusOr<SessionResult> result = Status(StatusCode::kInternal, "not run");
};

struct MeshRowsCallbacks {
  // Progress of input `index` (the report's candidate and candidates are its own).
  std::function<void(int32_t index, const GenerateProgress&)> progress;
  CancelCheck cancel;  // polled before every id, in pre-processing and scoring: stops the batch
};

class MeshRows {
 public:
  explicit MeshRows(const Model& model);
  MeshRows(const MeshRows&) = delete;
  MeshRows& operator=(const MeshRows&) = delete;

  // A new batch (any previous one is dropped): at most `parallel` meshes in flight
  // (ranges::kParallel) over parallel x `rows` decoder rows in all (ranges::kRows); each mesh's
  // candidates take at most min(its request's rows, its candidates) of them at once, as alone.
  Status Open(int32_t parallel, int32_t rows, const MeshRowsCallbacks& callbacks = {});
  // Queues an input; returns its index (0, 1, ... in the order added). The request is resolved and
  // the input prepared into encoder points now; an error there is the input's result (Next).
  int32_t Add(const GenerationRequest& request, const GenerationInput& input);
  // Queues an input that failed before it could be added (e.g. its C params): `error` is its result.
  int32_t AddError(Status error);
  // Runs until an input ends and returns it (a failed one included: its error). InvalidArgument
  // when no input is queued or in flight. A cancel (kCancelled) ends every input in flight with
  // kCancelled results, to be taken by the following calls, and the queued ones too, unstarted
  // ("cancelled before it started"): every input added comes back exactly once.
  StatusOr<MeshRowsEnded> Next();
  // Thread-safe, any time: stops an encoder run in progress.
  void InterruptEncoder();

  int32_t parallel() const { return parallel_; }
  int32_t in_flight() const { return static_cast<int32_t>(flight_.size()); }  // encoded, not ended
  int32_t queued() const { return static_cast<int32_t>(queue_.size()); }      // added, not started
  bool idle() const { return queue_.empty() && flight_.empty() && ended_.empty(); }

 private:
  struct Input {  // an input added, prepared
    int32_t index = 0;
    StatusOr<PreparedInput> prepared = Status(StatusCode::kInternal, "not prepared");
    GenerationRequest request;
    GenerationInput input;  // kept only for the one-after-another path
    Status error;           // AddError's
  };
  struct Flight {  // an input whose candidates run as rows
    int32_t index = 0;
    PreparedInput prepared;
    CandidateChoice choice;
    std::vector<std::optional<GenerateResult>> waiting;  // ended, by candidate, not yet scored
    std::chrono::steady_clock::time_point started;
  };
  bool ByRows() const;
  StatusOr<MeshRowsEnded> NextAlone();
  // Encodes queued inputs while a source is free (failures end at once, into ended_).
  Status Admit();
  // The rows' ended candidates scored in order per mesh; a mesh with all scored is concluded.
  Status Collect();
  void Conclude(int32_t mesh);
  Status CancelAll(Status why);
  // A cancel: every queued input ends kCancelled without starting.
  void EndQueued();
  bool Cancelled() const { return CancelRequested(callbacks_.cancel); }

  const Model& model_;
  GenerationSession session_;  // one after another
  CandidateRows rows_;
  MeshRowsCallbacks callbacks_;
  int32_t parallel_ = 1, rows_per_mesh_ = 1, added_ = 0;
  std::deque<Input> queue_;
  std::map<int32_t, Flight> flight_;  // by CandidateRows mesh id
  std::deque<MeshRowsEnded> ended_;
};

}  // namespace silk
