// SPDX-License-Identifier: MIT
// Generator: one constrained generation, encoder points -> token ids -> grid mesh, step-wise
// (Start, Step until finished, MeshSoFar at any point, Finish; Run loops over them). Holds the
// KV cache between runs (reuse one Generator per thread). Callers that start from an input and
// want best of N use GenerationSession (runtime/generation_session.h), which runs its candidates
// on one Generator. Each id the grammar does not force comes from the sampling chain
// (runtime/sampling/sampler.h: grammar mask, surface guidance when on, then the numeric stages), built once
// per generation; forced ids are appended without sampling and fed to the model later as one
// chunk together with the next sampled id (chunked prefill).
#pragma once
#include <cstdint>
#include <functional>
#include <memory>
#include <utility>
#include <vector>

#include "core/cancel_check.h"
#include "core/status.h"
#include "decoder/mesh_builder.h"
#include "runtime/generation_stats.h"
#include "runtime/kv_cache.h"
#include "runtime/model/model.h"
#include "runtime/sampling/face_guide.h"
#include "runtime/sampling/sampler.h"

namespace Ort {
struct RunOptions;
struct Value;
}  // namespace Ort

namespace silk {

class SurfaceGuide;
class FaceGuide;
class OrientedPointSet;

struct GenerateOptions {
  SamplingParams sampling;
  int32_t max_tokens = 0;  // ids incl. EOS; 0 = the model's max_seq_len - 1
  int32_t max_faces = 0;   // stop at the first layer close with at least this many faces; 0 = off
  HolePolicy holes = HolePolicy::kOff;
  // No grammar mask: ids as the model draws them, as the official network's own loop does (the
  // grammar only watches; mesh = legal prefix). In-tree comparisons only (capi/capi_measurement.h).
  bool unconstrained = false;
  bool record_trace = false;  // fill GenerateResult::trace (golden test reference check)
  // Surface guidance (runtime/sampling/surface_guide.h): vertex ids only on grid cells within this many
  // cells of an input point's cell; 0 = off. Constrained mode only: with `unconstrained` there
  // is no mask to restrict, so the setting is ignored (stats.guided_tokens stays 0).
  int32_t surface_tolerance = 0;
  // Best of N: the candidates GenerationSession runs (runtime/generation_session.h), each a
  // Generator run with a derived seed. A Generator runs one generation and ignores it.
  int32_t candidates = 1;
  // Best of N: candidates decoded together (GenerationSession); a Generator runs one generation and ignores it.
  int32_t rows = 1;
  // Part orientation (runtime/input_orientation.h): every generated part whose winding
  // disagrees with the encoder's points' normals (area-weighted vote) is reversed, in the final
  // mesh and in MeshSoFar. Off = the winding the ids carry (what decoding the token file gives).
  bool orient_to_input = false;
  // Face guidance (runtime/sampling/face_guide_stage.h): between-layer ids judged by the faces
  // they would close, against the input's points (face_tolerance cells, FaceGuide's score);
  // hard removes the ones that stray, soft lowers their logits. Constrained mode only.
  FaceGuidance face_guidance = FaceGuidance::kOff;
  double face_tolerance = 2.0;
};

struct GenerateProgress {
  int64_t tokens = 0, max_tokens = 0;
  int32_t components = 0;                 // started so far
  int32_t faces = -1;                     // at the last layer close, when max_faces is set; else -1
  double seconds = 0;                     // since the candidate's Start
  int32_t candidate = 0, candidates = 1;  // best of N: the one generating (GenerationSession)
};

struct GenerateCallbacks {
  std::function<void(const GenerateProgress&)> progress;  // after every id, the last one included
  // Polled before the encoder and every id (GenerationSession: during point sampling too);
  // true: stop (kCancelled).
  std::function<bool()> cancel;
};

// One generated id, for the reference check: forced or sampled, and the legal set it was
// sampled from (ascending [begin, end) ranges; empty when forced or unconstrained).
struct TraceStep {
  int32_t id = 0;
  bool forced = false;
  std::vector<std::pair<int32_t, int32_t>> legal;
  std::vector<std::pair<int32_t, float>> penalties;  // soft face guidance: (id, logit penalty)
  FaceVerdict face = FaceVerdict::kNotJudged;        // face guidance: passed, fallback or not judged
};

struct GenerateResult {
  std::vector<int32_t> tokens;  // EOS included when reached; no BOS
  TokenizerDecodedMesh mesh;    // grid coordinates
  MeshBuildReport report;
  GenerationStats stats;
  std::vector<TraceStep> trace;
};

// Checks options before any work: every value by the settings' range table
// (runtime/sampling/generation_ranges.h) and the face guidance mode.
Status CheckGenerateOptions(const GenerateOptions& options);

class Generator {
 public:
  explicit Generator(const Model& model);
  ~Generator();
  // `points`: n rows of 6 floats in the model's normalised frame (xyz, unit normal).
  StatusOr<GenerateResult> Run(const std::vector<float>& points, const GenerateOptions& options,
                               const GenerateCallbacks& callbacks = {});

  // Step-wise: Start runs the encoder; each Step adds one id (finished() once a stop reason is
  // set); Finish builds the mesh and returns the result (also after a cancel: what was closed).
  // A failed Start or Step ends the generation (Finish then fails too).
  Status Start(const std::vector<float>& points, const GenerateOptions& options,
               const GenerateCallbacks& callbacks = {});
  Status Step();
  bool active() const { return session_ != nullptr; }
  bool finished() const;
  // Marks the generation cancelled (StopReason::kCancelled); Finish still returns its stats.
  void Cancel();
  // Thread-safe, any time: stops an encoder run in progress (Start then fails; it answers
  // kCancelled when callbacks.cancel says so, which is how a caller asks for both).
  void InterruptEncoder();
  const std::vector<int32_t>& tokens() const;
  const GenerationStats& stats() const;
  // Faces of the layers completed so far (grid coordinates).
  StatusOr<TokenizerDecodedMesh> MeshSoFar() const;
  // Completed layers so far (layer ends seen).
  int64_t layers_closed() const;
  // `cancel` is polled while the mesh is turned to the input's normals (orient_to_input: a query
  // per face into the encoder points, each up to all of them): kCancelled leaves the generation
  // as it was, to Finish again or Release.
  StatusOr<GenerateResult> Finish(const CancelCheck& cancel = {});
  // Ends the generation without building its mesh.
  void Release();

  // Rows mode (runtime/candidate_rows.h): a generation whose decoder calls the caller makes, for
  // many generations at once (RowsDecoder). StartRow is Start without the encoder run and the
  // cache: the caller ran the encoder (`encoder_seconds` goes into the stats) and feeds pending().
  Status StartRow(const std::vector<float>& points, const GenerateOptions& options, const GenerateCallbacks& callbacks,
                  double encoder_seconds);
  enum class RowStep { kStepped, kNeedsLogits, kEnded };
  // One id that needs no logits: a forced id is taken (kStepped); an id to sample is decided up to
  // the logits and held (kNeedsLogits, again until StepWithLogits); kEnded once finished. Polls
  // callbacks.cancel before each id, as Step does.
  StatusOr<RowStep> StepWithoutLogits();
  // The ids the decoder must take before the held id's logits (BOS first, forced runs, the last id).
  const std::vector<int32_t>& pending() const;
  bool waiting_for_logits() const;
  // The caller fed the first `fed` ids of pending() to the decoder (in `calls` runs taking
  // `seconds`): they leave it. The held id's logits are those after the last pending id.
  void NoteFed(double seconds, int64_t calls, int64_t fed);
  // Completes the held step with the logits after the ids fed (NoteFed first).
  Status StepWithLogits(const float* logits);
  // Shares `other`'s per-input state (surface and face guides, orientation index) when its last
  // input is `points`, so rows of one input build them once.
  void ShareInput(const Generator& other, const std::vector<float>& points);

 private:
  struct Session;
  struct StepChoice;
  // StepOnce's phases, in order: grammar (forced id, legal mask), decoder over the pending ids,
  // sampling, trace, grammar Accept, append and stop checks.
  Status StepOnce();
  // Start's part after the encoder (both modes; CacheInput(points) already called once): the
  // session, its stats, guides and chain.
  Status Begin(const std::vector<float>& points, const GenerateOptions& options, const GenerateCallbacks& callbacks,
               int32_t cap, double encoder_seconds);
  StatusOr<int32_t> CheckStart(const std::vector<float>& points, const GenerateOptions& options) const;
  Status AttachInput(const std::vector<float>& points, const GenerateOptions& options,
                     const GenerateCallbacks& callbacks);
  bool ConsultGrammar(StepChoice* choice);
  Status FeedPending();
  Status CheckLogits(const float* logits) const;
  // The step after the grammar: sample unless forced (from `logits`), trace, Accept, append.
  Status TakeId(StepChoice* choice, const float* logits);
  void ChooseId(StepChoice* choice, const float* logits);
  void RecordTrace(const StepChoice& choice);
  Status AcceptId(int32_t id);
  void AppendId(int32_t id);
  void CheckFaceCap();
  void ReportProgress();
  const Model& model_;
  KvCache cache_;
  // What the last input's points gave: runs on the same input (best of N) build each once.
  // A different input clears them all (CacheInput).
  void CacheInput(const std::vector<float>& points);
  std::vector<float> input_points_;
  std::shared_ptr<Ort::Value> cross_;  // the encoder output (Start; rows mode: the caller's)
  std::shared_ptr<const SurfaceGuide> guide_;
  std::shared_ptr<const FaceGuide> face_guide_;
  std::shared_ptr<const OrientedPointSet> orientation_;
  std::unique_ptr<Session> session_;
  std::unique_ptr<Ort::RunOptions> encoder_run_;  // the encoder's run options (terminate flag)
};

}  // namespace silk
