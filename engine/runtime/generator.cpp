// SPDX-License-Identifier: MIT
// The generation loop: encoder once (Start), then per id (Step): grammar (forced? legal mask) ->
// decoder for the pending known ids -> finite check of the logits -> sampling chain -> Accept.
// Stops at EOS, at the token cap (the grammar's length budget makes constrained sequences end
// with EOS inside it), at the face cap, or on cancel.
#include "runtime/generator.h"

#include <algorithm>
#include <chrono>
#include <optional>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "core/value_text.h"
#include "decoder/face_cap.h"
#include "decoder/grammar.h"
#include "runtime/decoder_runner.h"
#include "runtime/input_orientation.h"
#include "runtime/model/model_impl.h"
#include "runtime/sampling/generation_ranges.h"
#include "runtime/sampling/surface_guide.h"
#include "tokenizer/vocabulary_layout.h"

namespace silk {

namespace {

using Clock = std::chrono::steady_clock;
double Since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

std::vector<std::pair<int32_t, int32_t>> MaskRanges(const TokenMask& m) {
  std::vector<std::pair<int32_t, int32_t>> r;
  for (int32_t id = m.Next(0); id >= 0; id = m.Next(id + 1)) {
    if (!r.empty() && r.back().second == id)
      r.back().second = id + 1;
    else
      r.push_back({id, id + 1});
  }
  return r;
}

// "N ids (last: a b c ...)" for internal-error messages.
std::string TailText(const std::vector<int32_t>& ids) {
  std::string s = std::to_string(ids.size()) + " ids (last:";
  for (size_t i = ids.size() > 24 ? ids.size() - 24 : 0; i < ids.size(); ++i) s += " " + std::to_string(ids[i]);
  return s + ")";
}

bool ClosesLayer(int32_t id) { return id == vocab::kUBegin || id == vocab::kEBegin; }

// Index of the first non-finite logit, or -1.
int64_t FirstNonFinite(const float* logits, int64_t n) {
  for (int64_t i = 0; i < n; ++i)
    if (!std::isfinite(logits[i])) return i;
  return -1;
}

// The sampling chain of one generation: the grammar mask unless unconstrained, then the guide
// (set only when constrained), the sampling values.
SamplerChainSettings ChainSettings(const GenerateOptions& o, Grammar* grammar, const SurfaceGuide* guide,
                                   const FaceGuide* face_guide, GenerationStats* stats) {
  SamplerChainSettings c;
  c.sampling = o.sampling;
  c.grammar = o.unconstrained ? nullptr : grammar;
  c.guide = guide;
  c.face_guide = face_guide;
  c.face_mode = o.face_guidance;
  c.stats = stats;
  return c;
}

}  // namespace

Status CheckGenerateOptions(const GenerateOptions& options) {
  const SamplingParams& sp = options.sampling;
  for (const auto& [range, value] : {std::pair{ranges::kMaxTokens, double(options.max_tokens)},
                                     {ranges::kMaxFaces, double(options.max_faces)},
                                     {ranges::kTemperature, sp.temperature},
                                     {ranges::kTopK, double(sp.top_k)},
                                     {ranges::kTopP, sp.top_p},
                                     {ranges::kTopPTemperature, sp.top_p_temperature},
                                     {ranges::kSurfaceTolerance, double(options.surface_tolerance)},
                                     {ranges::kFaceTolerance, options.face_tolerance},
                                     {ranges::kCandidates, double(options.candidates)},
                                     {ranges::kRows, double(options.rows)}})
    SILK_RETURN_IF_ERROR(CheckSetting(range, value).WithContext("generate: "));
  if (options.face_guidance != FaceGuidance::kOff && options.face_guidance != FaceGuidance::kHard &&
      options.face_guidance != FaceGuidance::kSoft)
    return InvalidArgument("generate: face_guidance " + std::to_string(static_cast<int32_t>(options.face_guidance)) +
                           " is not off (0), hard (1) or soft (2)");
  return Status::Ok();
}

// What one step decides: the id, whether the grammar forced it, and the legal set it is sampled
// from (null when unconstrained).
struct Generator::StepChoice {
  int32_t id = -1;
  bool forced = false;
  const TokenMask* mask = nullptr;
  const std::vector<std::pair<int32_t, float>>* penalties = nullptr;  // soft face guidance
  FaceVerdict face = FaceVerdict::kNotJudged;                         // face guidance's verdict
};

// One generation in progress: the encoder output and the decoder runner over the KV cache (none in
// rows mode: the caller feeds the decoder), the grammar and the sampling chain, the ids so far.
struct Generator::Session {
  Session(const GenerateOptions& o, const GenerateCallbacks& cb, int32_t cap)
      : options(o), callbacks(cb), cap(cap), grammar(MakeGrammarOptions(cap)) {}
  static GrammarOptions MakeGrammarOptions(int32_t cap) {
    GrammarOptions g;
    g.max_length = cap;
    return g;
  }
  GenerateOptions options;
  GenerateCallbacks callbacks;
  int32_t cap;
  std::shared_ptr<Ort::Value> cross;      // the input's encoder output (Generator::cross_)
  std::unique_ptr<DecoderRunner> runner;  // null in rows mode
  std::optional<StepChoice> held;         // rows mode: a step waiting for its logits
  int64_t row_calls = 0, row_fed = 0;     // rows mode: decoder runs taken part in, positions fed
  Grammar grammar;
  std::unique_ptr<SamplerChain> chain;  // built in Start, once the guide is known
  GenerateResult res;
  std::vector<int32_t> pending;
  int32_t faces_at_close = -1;
  int64_t layers_closed = 0;
  std::shared_ptr<const SurfaceGuide> guide;            // surface_tolerance > 0, constrained mode
  std::shared_ptr<const FaceGuide> face_guide;          // face_guidance on, constrained mode
  std::shared_ptr<const OrientedPointSet> orientation;  // orient_to_input
  mutable MeshBuildCache so_far_cache;                  // max_faces / MeshSoFar: closed components are built once
  bool illegal_seen = false;
  bool failed = false;
  Clock::time_point t_start, t_loop;
};

Generator::Generator(const Model& model) : model_(model), encoder_run_(std::make_unique<Ort::RunOptions>()) {}
Generator::~Generator() = default;

bool Generator::finished() const { return session_ && session_->res.stats.stop_reason != StopReason::kNone; }
const std::vector<int32_t>& Generator::tokens() const {
  static const std::vector<int32_t> kNone;
  return session_ ? session_->res.tokens : kNone;
}
const GenerationStats& Generator::stats() const {
  static const GenerationStats kNone;
  return session_ ? session_->res.stats : kNone;
}
int64_t Generator::layers_closed() const { return session_ ? session_->layers_closed : 0; }

void Generator::Cancel() {
  if (session_ && !finished()) session_->res.stats.stop_reason = StopReason::kCancelled;
}

void Generator::InterruptEncoder() { encoder_run_->SetTerminate(); }

void Generator::CacheInput(const std::vector<float>& points) {
  if (points == input_points_) return;
  input_points_ = points;
  cross_.reset();
  guide_.reset();
  face_guide_.reset();
  orientation_.reset();
}

// The token cap of a generation (ids incl. EOS after BOS), after checking its points and options.
StatusOr<int32_t> Generator::CheckStart(const std::vector<float>& points, const GenerateOptions& options) const {
  const ModelConfig& cfg = model_.impl().config;
  if (points.empty() || points.size() % 6 != 0)
    return InvalidArgument("generate: points must be a non-empty array of rows of 6 floats");
  SILK_RETURN_IF_ERROR(CheckGenerateOptions(options));
  const int32_t model_cap = cfg.dims.max_seq_len - 1;
  const int32_t cap = options.max_tokens > 0 ? std::min(options.max_tokens, model_cap) : model_cap;
  if (cap < kMinMeshTokens)
    return InvalidArgument(cfg.dir + "/model.json: max_seq_len " + std::to_string(cfg.dims.max_seq_len) +
                           " leaves room for fewer ids than the smallest mesh (" + std::to_string(kMinMeshTokens) +
                           ")");
  return cap;
}

Status Generator::Start(const std::vector<float>& points, const GenerateOptions& options,
                        const GenerateCallbacks& callbacks) {
  session_.reset();
  const Model::Impl& m = model_.impl();
  SILK_ASSIGN_OR_RETURN(const int32_t cap, CheckStart(points, options));
  // Encoder: cross-attention K/V once per input, kept for the next run on it (the candidates of
  // a best of N run one after another on the same points). A terminate request left from an
  // earlier run is dropped before the poll; one made after it stops the run (InterruptEncoder).
  CacheInput(points);
  double encoder_seconds = 0;
  if (!cross_) {
    encoder_run_->UnsetTerminate();
    const auto t0 = Clock::now();
    SILK_ASSIGN_OR_RETURN(Ort::Value cross, EncodeInput(m, points, *encoder_run_, callbacks.cancel));
    cross_ = std::make_shared<Ort::Value>(std::move(cross));
    encoder_seconds = Since(t0);
  } else if (callbacks.cancel && callbacks.cancel()) {
    return Status(StatusCode::kCancelled, "generation cancelled");
  }
  // Cache: BOS + every id but the last (EOS is never fed).
  SILK_RETURN_IF_ERROR(cache_.Reserve(cap, ModelKvShape(m)));
  SILK_RETURN_IF_ERROR(Begin(points, options, callbacks, cap, encoder_seconds));
  session_->cross = cross_;
  session_->runner = std::make_unique<DecoderRunner>(m, &cache_, session_->cross->GetTensorMutableData<void>());
  return Status::Ok();
}

Status Generator::StartRow(const std::vector<float>& points, const GenerateOptions& options,
                           const GenerateCallbacks& callbacks, double encoder_seconds) {
  session_.reset();
  SILK_ASSIGN_OR_RETURN(const int32_t cap, CheckStart(points, options));
  if (callbacks.cancel && callbacks.cancel()) return Status(StatusCode::kCancelled, "generation cancelled");
  CacheInput(points);
  return Begin(points, options, callbacks, cap, encoder_seconds);
}

void Generator::ShareInput(const Generator& other, const std::vector<float>& points) {
  if (&other == this || other.input_points_ != points) return;
  input_points_ = other.input_points_;
  guide_ = other.guide_;
  face_guide_ = other.face_guide_;
  orientation_ = other.orientation_;
}

Status Generator::Begin(const std::vector<float>& points, const GenerateOptions& options,
                        const GenerateCallbacks& callbacks, int32_t cap, double encoder_seconds) {
  const Model::Impl& m = model_.impl();
  session_ = std::make_unique<Session>(options, callbacks, cap);
  Session& s = *session_;
  s.t_start =
      Clock::now() - std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(encoder_seconds));
  GenerationStats& st = s.res.stats;
  st.threads = m.threads;
  st.int8 = m.precision == DecoderPrecision::kInt8;
  st.decoder = DecoderPrecisionName(m.precision);
  st.seconds.encoder = encoder_seconds;
  st.kv_precision = KvPrecisionName(m.kv_precision);
  st.model_version = m.config.model_version;
  st.decoder_contract = m.rows_contract ? kRowsModelVersion : 3;
  st.kv_cache_bytes = cap * ModelKvShape(m).position_bytes();
  if (Status guided = AttachInput(points, options, callbacks); !guided.ok()) {
    session_.reset();
    return guided;
  }
  s.chain = BuildSamplerChain(ChainSettings(options, &s.grammar, s.guide.get(), s.face_guide.get(), &st));
  s.pending = {m.config.bos_id};
  s.t_loop = Clock::now();
  return Status::Ok();
}

// The per-input state the options ask for (built once per input, kept for the next run on it).
Status Generator::AttachInput(const std::vector<float>& points, const GenerateOptions& options,
                              const GenerateCallbacks& callbacks) {
  Session& s = *session_;
  GenerationStats& st = s.res.stats;
  if (options.surface_tolerance > 0 && !options.unconstrained) {
    const auto t0 = Clock::now();
    if (!guide_ || guide_->tolerance() != options.surface_tolerance)
      guide_ = std::make_shared<const SurfaceGuide>(points, options.surface_tolerance);
    s.guide = guide_;
    st.seconds.guidance += Since(t0);
  }
  if (options.face_guidance != FaceGuidance::kOff && !options.unconstrained) {
    const auto t0 = Clock::now();
    if (!face_guide_ || face_guide_->tolerance() != options.face_tolerance) {
      // The distance field is surface guidance's; its tolerance does not matter here.
      auto field = guide_ ? guide_ : std::make_shared<const SurfaceGuide>(points, 1);
      face_guide_ = std::make_shared<const FaceGuide>(field, points, options.face_tolerance);
    }
    s.face_guide = face_guide_;
    st.seconds.face_guidance += Since(t0);
  }
  if (options.orient_to_input) {
    if (!orientation_) {
      SILK_ASSIGN_OR_RETURN(orientation_, MakeInputOrientation(points, callbacks.cancel));
    }
    s.orientation = orientation_;
  }
  return Status::Ok();
}

Status Generator::Step() {
  if (!session_ || session_->failed) return InvalidArgument("generate: no generation in progress (Start first)");
  if (finished()) return Status::Ok();
  Session& s = *session_;
  Status status = StepOnce();
  if (!status.ok() && status.code() != StatusCode::kCancelled) s.failed = true;
  return status;
}

Status Generator::StepOnce() {
  Session& s = *session_;
  if (s.callbacks.cancel && s.callbacks.cancel()) {
    s.res.stats.stop_reason = StopReason::kCancelled;
    return Status(StatusCode::kCancelled, "generation cancelled");
  }
  StepChoice c;
  if (!s.options.unconstrained && !ConsultGrammar(&c)) return Status::Ok();  // dead end: stop reason set
  if (c.forced) return TakeId(&c, nullptr);                                  // a forced id needs no logits
  SILK_RETURN_IF_ERROR(FeedPending());
  return TakeId(&c, s.runner->last_logits());
}

Status Generator::TakeId(StepChoice* c, const float* logits) {
  ChooseId(c, logits);
  RecordTrace(*c);
  SILK_RETURN_IF_ERROR(AcceptId(c->id));
  AppendId(c->id);
  ReportProgress();
  return Status::Ok();
}

StatusOr<Generator::RowStep> Generator::StepWithoutLogits() {
  if (!session_ || session_->failed) return InvalidArgument("generate: no generation in progress (Start first)");
  if (finished()) return RowStep::kEnded;
  Session& s = *session_;
  if (s.held) return RowStep::kNeedsLogits;
  if (s.callbacks.cancel && s.callbacks.cancel()) {
    s.res.stats.stop_reason = StopReason::kCancelled;
    return Status(StatusCode::kCancelled, "generation cancelled");
  }
  StepChoice c;
  if (!s.options.unconstrained && !ConsultGrammar(&c)) return RowStep::kEnded;  // dead end: stop reason set
  if (!c.forced) {
    s.held = c;
    return RowStep::kNeedsLogits;
  }
  Status status = TakeId(&c, nullptr);
  if (!status.ok()) {
    s.failed = status.code() != StatusCode::kCancelled;
    return status;
  }
  return RowStep::kStepped;
}

const std::vector<int32_t>& Generator::pending() const {
  static const std::vector<int32_t> kNone;
  return session_ ? session_->pending : kNone;
}

bool Generator::waiting_for_logits() const { return session_ && session_->held.has_value(); }

void Generator::NoteFed(double seconds, int64_t calls, int64_t fed) {
  if (!session_) return;
  Session& s = *session_;
  s.res.stats.seconds.decoder += seconds;
  s.row_calls += calls;
  fed = std::clamp<int64_t>(fed, 0, static_cast<int64_t>(s.pending.size()));
  s.row_fed += fed;
  s.pending.erase(s.pending.begin(), s.pending.begin() + fed);
}

Status Generator::StepWithLogits(const float* logits) {
  if (!session_ || session_->failed || !session_->held || !session_->pending.empty())
    return InvalidArgument("generate: no step is waiting for logits");
  Session& s = *session_;
  StepChoice c = *s.held;
  s.held.reset();
  Status status = CheckLogits(logits);
  if (status.ok()) status = TakeId(&c, logits);
  if (!status.ok()) s.failed = true;
  return status;
}

// The chain's stages before the logits: the grammar's forced id (or -1) and legal mask, guided
// when surface guidance is on. False at a dead end (no legal id), with the stop reason set.
bool Generator::ConsultGrammar(StepChoice* c) {
  Session& s = *session_;
  GenerationStats& st = s.res.stats;
  const SamplerCandidates& narrowed = s.chain->Narrow();
  c->id = narrowed.forced;
  c->mask = narrowed.mask;
  c->penalties = narrowed.penalties;
  c->face = narrowed.face;
  if (c->mask->Empty()) {
    // Cannot happen if the grammar's liveness guarantee holds; stop with what is closed
    // rather than fail the whole run, and say so in the stats.
    st.stop_reason = StopReason::kGrammarDeadEnd;
    st.dead_end = "no legal id after " + TailText(s.res.tokens);
    return false;
  }
  c->forced = c->id >= 0;
  return true;
}

// Runs the decoder over the pending known ids, then checks its logits are finite.
Status Generator::FeedPending() {
  Session& s = *session_;
  const auto t0 = Clock::now();
  SILK_RETURN_IF_ERROR(s.runner->Feed(s.pending.data(), static_cast<int64_t>(s.pending.size())));
  s.res.stats.seconds.decoder += Since(t0);
  s.pending.clear();
  return CheckLogits(s.runner->last_logits());
}

Status Generator::CheckLogits(const float* logits) const {
  const int64_t bad = FirstNonFinite(logits, model_.config().model_vocab_size);
  if (bad >= 0)
    return InternalError(model_.config().dir + ": the decoder produced a non-finite logit (id " + std::to_string(bad) +
                         ") after " + std::to_string(session_->res.tokens.size()) +
                         " ids; the model's weights are corrupt (NaN or infinite)");
  return Status::Ok();
}

// Samples the id unless the grammar forced it: the chain's stages on the logits.
void Generator::ChooseId(StepChoice* c, const float* logits) {
  Session& s = *session_;
  GenerationStats& st = s.res.stats;
  if (c->forced) {
    ++st.forced_tokens;
    return;
  }
  const auto t0 = Clock::now();
  c->id = s.chain->Sample(logits, c->mask);
  st.seconds.sampling += Since(t0);
  ++st.sampled_tokens;
}

void Generator::RecordTrace(const StepChoice& c) {
  Session& s = *session_;
  if (!s.options.record_trace) return;
  TraceStep step;
  step.id = c.id;
  step.forced = c.forced;
  if (!c.forced && c.mask) step.legal = MaskRanges(*c.mask);
  if (!c.forced && c.penalties) step.penalties = *c.penalties;
  step.face = c.face;
  s.res.trace.push_back(std::move(step));
}

// Feeds the id to the grammar: constrained, a rejection is an internal error; unconstrained,
// the grammar only watches and the first illegal id is noted in the stats.
Status Generator::AcceptId(int32_t id) {
  Session& s = *session_;
  GenerationStats& st = s.res.stats;
  const auto t0 = Clock::now();
  if (!s.options.unconstrained) {
    Rejection r = s.grammar.Accept(id);
    if (!r.ok())
      return InternalError("generate: id " + std::to_string(id) + " was rejected after " + TailText(s.res.tokens) +
                           ": " + r.message);
  } else if (!s.illegal_seen) {
    Rejection r = s.grammar.Accept(id);
    if (!r.ok()) {
      s.illegal_seen = true;
      st.illegal_at = static_cast<int64_t>(s.res.tokens.size());
      st.illegal_reason = r.message;
    }
  }
  st.seconds.grammar += Since(t0);
  return Status::Ok();
}

// Appends the id and sets the stop reason it brings (EOS, the token cap, the face cap at a
// layer close); otherwise queues it for the decoder.
void Generator::AppendId(int32_t id) {
  Session& s = *session_;
  GenerationStats& st = s.res.stats;
  s.res.tokens.push_back(id);
  st.tokens = static_cast<int64_t>(s.res.tokens.size());
  if (id == vocab::k_eos_id) {
    st.stop_reason = StopReason::kEos;
  } else if (static_cast<int32_t>(s.res.tokens.size()) >= s.cap) {
    st.stop_reason = StopReason::kMaxTokens;
  } else {
    s.pending.push_back(id);
    if (ClosesLayer(id) && !s.illegal_seen) ++s.layers_closed;
    if (s.options.max_faces > 0 && !s.illegal_seen && ClosesLayer(id)) CheckFaceCap();
  }
}

// At a layer close: the faces built so far, and the stop reason once they reach max_faces.
void Generator::CheckFaceCap() {
  Session& s = *session_;
  GenerationStats& st = s.res.stats;
  const auto t0 = Clock::now();
  auto so_far = BuildMeshSoFar(s.grammar, MeshBuildOptions{}, nullptr, &s.so_far_cache);
  st.seconds.build_mesh += Since(t0);
  if (so_far.ok()) s.faces_at_close = static_cast<int32_t>(so_far->faces.size());
  if (s.faces_at_close >= s.options.max_faces) st.stop_reason = StopReason::kMaxFaces;
}

void Generator::ReportProgress() {
  Session& s = *session_;
  if (!s.callbacks.progress) return;
  GenerateProgress p;
  p.tokens = static_cast<int64_t>(s.res.tokens.size());
  // The bar reaches 100 % on the last id, whatever stopped the generation.
  p.max_tokens = s.res.stats.stop_reason == StopReason::kNone ? s.cap : p.tokens;
  p.components = static_cast<int32_t>(s.grammar.stream().components.size());
  p.faces = s.faces_at_close;
  p.seconds = Since(s.t_start);
  s.callbacks.progress(p);
}

StatusOr<TokenizerDecodedMesh> Generator::MeshSoFar() const {
  if (!session_) return InvalidArgument("generate: no generation in progress");
  if (session_->options.unconstrained && session_->illegal_seen) return TokenizerDecodedMesh{};
  SILK_ASSIGN_OR_RETURN(TokenizerDecodedMesh mesh,
                        BuildMeshSoFar(session_->grammar, MeshBuildOptions{}, nullptr, &session_->so_far_cache));
  if (session_->options.max_faces > 0) mesh = CapFaces(mesh, session_->options.max_faces);
  if (session_->orientation) OrientToInput(&mesh, *session_->orientation);
  return mesh;
}

void Generator::Release() { session_.reset(); }

StatusOr<GenerateResult> Generator::Finish(const CancelCheck& cancel) {
  if (!session_ || session_->failed) return InvalidArgument("generate: no generation to finish");
  if (!finished()) Cancel();
  Session& s = *session_;
  GenerateResult& res = s.res;
  GenerationStats& st = res.stats;
  const double loop_seconds = Since(s.t_loop);
  st.tokens = static_cast<int64_t>(res.tokens.size());
  st.model_calls = s.runner ? s.runner->calls() : s.row_calls;
  st.fed_positions = s.runner ? cache_.length() : s.row_fed;
  st.tokens_per_second = loop_seconds > 0 ? st.tokens / loop_seconds : 0;
  st.generation_seconds = Since(s.t_start);

  // Mesh: the whole sequence when it ended legally, else what the grammar closed so far.
  auto t0 = Clock::now();
  res.report = MeshBuildReport{};  // a Finish again after a cancelled one starts afresh
  MeshBuildOptions bopt;
  bopt.holes = s.options.holes;
  const bool complete = !s.options.unconstrained
                            ? st.stop_reason == StopReason::kEos || st.stop_reason == StopReason::kMaxTokens
                            : (!s.illegal_seen && s.grammar.Ended());
  if (complete) {
    SILK_ASSIGN_OR_RETURN(res.mesh, BuildMesh(s.grammar.stream(), bopt, &res.report));
  } else {
    SILK_ASSIGN_OR_RETURN(res.mesh, BuildMeshSoFar(s.grammar, bopt, &res.report));
  }
  if (s.options.max_faces > 0) res.mesh = CapFaces(res.mesh, s.options.max_faces);  // the last layer may overshoot
  if (s.orientation) {  // kCancelled leaves the session: Finish again (or Release)
    SILK_ASSIGN_OR_RETURN(const PartOrientationReport oriented, OrientToInput(&res.mesh, *s.orientation, cancel));
    st.parts_flipped = oriented.parts_flipped;
  }
  st.seconds.build_mesh += Since(t0);
  st.faces = static_cast<int32_t>(res.mesh.faces.size());
  st.vertices = static_cast<int32_t>(res.mesh.positions.size());
  st.components = res.mesh.components;
  st.holes_found = static_cast<int32_t>(res.report.holes.size());
  for (const HoleReport& h : res.report.holes) st.holes_repaired += h.repaired ? 1 : 0;
  st.faces_added = res.report.faces_added;
  st.fan_gaps_closed = res.report.fan_gaps_closed;
  st.vertices_split = res.report.vertices_split;
  st.window_findings = static_cast<int32_t>(res.report.window_findings.size());
  GenerateResult out = std::move(res);
  session_.reset();
  return out;
}

StatusOr<GenerateResult> Generator::Run(const std::vector<float>& points, const GenerateOptions& options,
                                        const GenerateCallbacks& callbacks) {
  SILK_RETURN_IF_ERROR(Start(points, options, callbacks));
  while (!finished()) SILK_RETURN_IF_ERROR(Step());
  return Finish();
}

}  // namespace silk
