// SPDX-License-Identifier: MIT
// GenerationSession: one generation as a caller runs it, step by step; the C API's step-wise
// generator and silk_generator_run are both loops over it. Start resolves the request against the
// model and prepares the input into the encoder's points; Advance generates ids, running best of
// N's candidates one after another on one Generator (rows 1), or up to `rows` of them at once
// (CandidateRows: the same ids, one decoder call per step for all); Preview shows the candidate in
// progress (with rows: the one furthest along);
// Finish scores and returns the chosen candidate in the input frame with verdicts and stats.
#pragma once
#include <chrono>
#include <cstdint>
#include <limits>
#include <optional>
#include <vector>

#include "core/cancel_check.h"
#include "core/status.h"
#include "io/io_mesh.h"
#include "mesh/normalize.h"
#include "runtime/candidate_rows.h"
#include "runtime/candidates.h"
#include "runtime/generation_input.h"
#include "runtime/generation_request.h"
#include "runtime/generator.h"
#include "runtime/input_generation.h"
#include "runtime/model/model.h"

namespace silk {

// Where Advance may stop before max_ids ids.
enum class AdvanceUntil {
  kIds,    // only at max_ids (or the end): candidates follow one another within the call
  kLayer,  // also after the next completed layer, and at the end of a candidate
};

// The completed layers of the candidate in progress, on the grid (parts) and in the input frame.
struct SessionPreview {
  TokenizerDecodedMesh grid;
  IoMesh output;
};

// One of best of N's candidates as the step-wise API shows it (every row, the best so far marked).
struct CandidateView {
  enum class State { kWaiting, kRunning, kEnded, kScored };  // not started / generating / built / scored
  int32_t index = 0;
  State state = State::kWaiting;
  int64_t tokens = 0;
  int32_t faces = -1;                                       // built (ended, scored): its mesh's faces
  double score = std::numeric_limits<double>::quiet_NaN();  // scored only
  bool best = false;                                        // the chosen one of those scored so far
};

class GenerationSession {
 public:
  explicit GenerationSession(const Model& model);
  GenerationSession(const GenerationSession&) = delete;
  GenerationSession& operator=(const GenerationSession&) = delete;

  // Discards a generation in progress, resolves `request` (ResolveRequest: its messages name the
  // field), checks `input`, prepares the encoder's points (the model's pre-processing, or raw
  // points) and starts candidate 0 (its encoder run). callbacks.cancel is polled where Generator
  // polls it (pre-processing, before each candidate's encoder run, the orientation index, before
  // every id) and in the scoring of a candidate before the last; `flag` (a caller's own cancel
  // flag) there too and in the input check.
  // Progress reports carry the candidate's index and N.
  Status Start(const GenerationRequest& request, const GenerationInput& input, const GenerateCallbacks& callbacks = {},
               const CancelCheck& flag = {});
  // Up to max_ids ids. When a candidate before the last has ended, the next call (kIds: the same
  // call) scores it (polling `flag`) and starts the next one (its encoder run). A cancel
  // (kCancelled) ends the run: done() and Finish returns what there is. Any other error fails it.
  Status Advance(int32_t max_ids, AdvanceUntil until = AdvanceUntil::kIds);
  // The chosen candidate of those generated: all N when done(), else (cancelled, or finished
  // early, which cancels) the ended ones and the one in progress with its completed layers, with
  // stop reason kCancelled. kCancelled from `scoring` leaves the session as it was (Finish again,
  // or Abandon); any other error ends it.
  StatusOr<SessionResult> Finish(const CancelCheck& scoring = {});
  // Ends the run without a result.
  void Abandon();
  // Thread-safe, any time: stops an encoder run in progress (Generator::InterruptEncoder).
  void InterruptEncoder() {
    generator_.InterruptEncoder();
    rows_.InterruptEncoder();
  }

  bool active() const { return active_; }  // started, not yet finished or abandoned
  bool done() const;                       // every candidate has ended, or a cancel ended the run
  int32_t candidate() const;               // the one in progress (0-based; with rows, the one furthest along)
  int32_t rows() const { return by_rows_ ? rows_.rows() : 1; }  // candidates decoded together
  int32_t candidates() const { return plan_.options.candidates; }
  // The candidate in progress (or ended, awaiting its score); empty when there is none.
  const std::vector<int32_t>& tokens() const;
  const GenerationStats& stats() const;
  // A run ended by a cancel, before Abandon: stats() (the candidate in progress or ended, if any)
  // with stop reason kCancelled and candidates listing every candidate started (the scored ones,
  // then the unscored one with score 0), chosen_candidate the last of them.
  GenerationStats CancelledStats() const;
  StatusOr<SessionPreview> Preview() const;
  // Every candidate of the run in progress (N entries; empty when none is active).
  std::vector<CandidateView> Candidates() const;
  // Candidate `index`'s mesh: its completed layers while it runs, its whole mesh once built (empty
  // before it starts).
  StatusOr<SessionPreview> PreviewCandidate(int32_t index) const;
  // The last started run's resolved request and encoder points (kept after Finish).
  const GenerationPlan& plan() const { return plan_; }
  const std::vector<float>& points() const { return points_; }
  // The same points in the input's frame (normalisation undone; normals as they are): rows of 6
  // doubles (silk_generator_copy_points, silkgen --save-points). Empty before the first Start.
  std::vector<double> InputFramePoints() const;

 private:
  GenerateCallbacks CandidateCallbacks(int32_t index);
  Status StartCandidate();
  Status CloseCandidate(const CancelCheck& cancel);
  Status NextCandidate();
  // Rows mode: the ended candidates, scored into the choice in candidate order (as one after another).
  Status ScoreEnded(const CancelCheck& cancel);
  Status AdvanceRows(int32_t max_ids, AdvanceUntil until);
  StatusOr<SessionResult> FinishRows(const CancelCheck& scoring);
  SessionResult Conclude(bool complete);
  CancelCheck ScoringCheck() const;
  // The generator a preview, tokens() and stats() show: the one in progress, or none.
  const Generator* Shown() const;
  // A failed step: kCancelled ends the run (finishable), anything else fails it.
  Status Note(Status status);
  void Reset();

  const Model& model_;
  Generator generator_;
  GenerationPlan plan_;
  std::vector<float> points_;
  NormalizeTransform transform_;  // model frame -> input frame (identity for raw points)
  double prepare_seconds_ = 0;
  GenerateCallbacks callbacks_;
  CancelCheck flag_;
  CandidateChoice choice_;
  std::optional<GenerateResult> ended_;  // a finished candidate whose scoring was cancelled
  CandidateRows rows_;
  bool by_rows_ = false;
  std::chrono::steady_clock::time_point started_;       // rows mode: the run's start (wall time)
  std::vector<std::optional<GenerateResult>> waiting_;  // rows mode: ended, by index, not yet scored
  struct LastEnded {  // rows mode: the candidate that ended last (tokens(), stats() once none runs)
    int32_t candidate = -1;
    std::vector<int32_t> tokens;
    GenerationStats stats;
  } last_ended_;
  std::vector<TokenizerDecodedMesh> built_;  // scored candidates' meshes, by index (previews)
  // Adds candidate `index`'s result to the choice (scored, polling `cancel`), keeping its mesh.
  Status Score(GenerateResult* result, int32_t index, const CancelCheck& cancel);
  const Generator* RunningGenerator(int32_t index) const;
  const GenerateResult* EndedResult(int32_t index) const;
  int32_t candidate_ = 0;
  bool active_ = false, cancelled_ = false, failed_ = false;
};

}  // namespace silk
