// C API: the step-wise generator (start / advance / query / cancel / finish) and the one-call
// silk_generate* conveniences over it. Input -> model points (once) -> tokens -> mesh in the
// input frame.
#if defined(SILK_HAVE_RUNTIME)
#include <chrono>
#include <cmath>
#include <cstring>
#include <memory>

#include "capi/capi_generator.h"
#include "runtime/candidates.h"

using silk::capi::BusyLock;
using silk::capi::Guard;
using silk::capi::Ok;
using silk::capi::SetError;

namespace {

using Clock = std::chrono::steady_clock;
constexpr int32_t kAllDebugFlags =
    SILK_DEBUG_NO_SKIP_FORCED | SILK_DEBUG_KV_COPY | SILK_DEBUG_SAMPLE_THEN_CHECK | SILK_DEBUG_RECORD_TRACE;

silk_status Busy(const char* function) {
  return SetError(SILK_ERR_BUSY, std::string(function) + ": generator busy (in use on another thread; use one generator per thread)");
}

// The N a call runs: the caller's, or the model's (model.json sampling.candidates) for SILK_MODEL_VALUE.
int32_t ResolvedCandidates(const silk_generate_params& p, const silk::ModelConfig& config) {
  return p.candidates == SILK_MODEL_VALUE ? config.candidates : p.candidates;
}

// Sampling fields: SILK_MODEL_VALUE (-1) or a value in range; nothing else is read as "the model's".
silk::Status CheckSamplingParams(const silk_generate_params& p) {
  using silk::capi::CheckModelValueOr;
  SILK_RETURN_IF_ERROR(CheckModelValueOr("temperature", p.temperature, HUGE_VAL));
  SILK_RETURN_IF_ERROR(CheckModelValueOr("top_k", p.top_k, INT32_MAX));
  SILK_RETURN_IF_ERROR(CheckModelValueOr("top_p", p.top_p, 1.0));
  SILK_RETURN_IF_ERROR(CheckModelValueOr("top_p_temperature", p.top_p_temperature, HUGE_VAL));
  if (p.candidates != SILK_MODEL_VALUE && (p.candidates < 1 || p.candidates > silk::kMaxCandidates))
    return silk::InvalidArgument("candidates " + std::to_string(p.candidates) +
                                 " is neither SILK_MODEL_VALUE (-1: the model's) nor in 1.." +
                                 std::to_string(silk::kMaxCandidates));
  return silk::Status::Ok();
}

// Every flag, enum, cap and sampling field of the C params; the message names the field and value.
silk::Status CheckParams(const silk_generate_params& p) {
  using silk::capi::CheckEnum;
  using silk::capi::CheckFlag;
  SILK_RETURN_IF_ERROR(CheckSamplingParams(p));
  SILK_RETURN_IF_ERROR(CheckEnum("holes", p.holes, SILK_HOLES_OFF, SILK_HOLES_REPAIR, "silk_hole_policy"));
  SILK_RETURN_IF_ERROR(CheckFlag("unconstrained", p.unconstrained));
  SILK_RETURN_IF_ERROR(CheckFlag("raw_points", p.raw_points));
  SILK_RETURN_IF_ERROR(CheckEnum("orient", p.orient, SILK_ORIENT_TOKENS, SILK_ORIENT_INPUT, "silk_orientation"));
  if (p.preprocessing != SILK_MODEL_VALUE)
    SILK_RETURN_IF_ERROR(CheckEnum("preprocessing", p.preprocessing, SILK_PREPROCESS_SILK, SILK_PREPROCESS_OFFICIAL,
                                   "silk_preprocess_kind (or SILK_MODEL_VALUE, -1)"));
  if (p.debug_flags & ~kAllDebugFlags)
    return silk::InvalidArgument("debug_flags " + std::to_string(p.debug_flags) + " has unknown bits");
  for (const auto& [field, value] : {std::pair<const char*, int32_t>{"max_tokens", p.max_tokens},
                                     {"max_faces", p.max_faces}, {"n_points", p.n_points}})
    if (value < 0) return silk::InvalidArgument(std::string(field) + " " + std::to_string(value) + " is negative");
  return silk::Status::Ok();
}

// Checks the C params and maps them onto the runtime's options; a SILK_MODEL_VALUE sampling
// field takes the model's (model.json "sampling").
silk::StatusOr<silk::GenerateOptions> ToOptions(const silk_generate_params& p, const silk::ModelConfig& config) {
  SILK_RETURN_IF_ERROR(CheckParams(p));
  silk::GenerateOptions o;
  o.sampling = config.sampling;
  o.sampling.seed = p.seed;
  if (p.temperature != SILK_MODEL_VALUE) o.sampling.temperature = p.temperature;
  if (p.top_k != SILK_MODEL_VALUE) o.sampling.top_k = p.top_k;
  if (p.top_p != SILK_MODEL_VALUE) o.sampling.top_p = p.top_p;
  if (p.top_p_temperature != SILK_MODEL_VALUE) o.sampling.top_p_temperature = p.top_p_temperature;
  o.max_tokens = p.max_tokens;
  o.max_faces = p.max_faces;
  o.holes = p.holes == SILK_HOLES_REPAIR ? silk::HolePolicy::kRepair
            : p.holes == SILK_HOLES_REPORT ? silk::HolePolicy::kReport : silk::HolePolicy::kOff;
  o.unconstrained = p.unconstrained != 0;
  o.skip_forced = !(p.debug_flags & SILK_DEBUG_NO_SKIP_FORCED);
  o.kv_in_place = !(p.debug_flags & SILK_DEBUG_KV_COPY);
  o.order = (p.debug_flags & SILK_DEBUG_SAMPLE_THEN_CHECK) ? silk::SampleOrder::kSampleThenCheck
                                                          : silk::SampleOrder::kMaskFirst;
  o.record_trace = (p.debug_flags & SILK_DEBUG_RECORD_TRACE) != 0;
  o.surface_tolerance = p.surface_tolerance;
  o.candidates = ResolvedCandidates(p, config);
  o.orient_to_input = p.orient == SILK_ORIENT_INPUT;
  SILK_RETURN_IF_ERROR(silk::CheckGenerateOptions(o));
  return o;
}

// The generator's own cancel flag alone (silk_generator_cancel): what the loops the caller's
// callback is not polled in (input conversion and checks, scoring) poll in chunks.
silk::CancelCheck FlagCheck(silk_generator* g) {
  return [g] { return g->cancelled(); };
}

// The user's callbacks plus the generator's own cancel flag (silk_generator_cancel).
silk::GenerateCallbacks ToCallbacks(silk_generator* g, const silk_generate_params& p) {
  silk::GenerateCallbacks cb;
  if (p.progress) {
    cb.progress = [fn = p.progress, user = p.user_data](const silk::GenerateProgress& x) {
      silk_generate_progress c{x.tokens, x.max_tokens, x.components, x.faces, x.seconds};
      fn(&c, user);
    };
  }
  cb.cancel = [g, fn = p.cancel, user = p.user_data]() {
    return g->cancelled() || (fn && fn(user) != 0);
  };
  return cb;
}

// The caller's input as the runtime's GenerationInput (mesh, point cloud, or raw points); polls
// `cancel` every kCancelPollInterval points (a million take ~10 ms to convert and check).
silk::StatusOr<silk::GenerationInput> ToInput(const silk_generate_input& in, const silk::CancelCheck& cancel) {
  if ((in.mesh != nullptr) == (in.points != nullptr)) return silk::InvalidArgument("give exactly one of mesh, points");
  silk::GenerationInput out;
  if (in.mesh) {
    out.mesh = in.mesh->mesh;
    out.normals = in.mesh->normals;
    out.point_cloud = out.mesh.triangles.empty() && !out.normals.empty();
  } else {
    if (in.n_points == 0) return silk::InvalidArgument("no points");
    if (in.n_points > (size_t{1} << 26)) return silk::InvalidArgument("more than 2^26 points");
    out.point_cloud = true;
    out.mesh.positions.resize(in.n_points);
    out.normals.resize(in.n_points);
    for (size_t i = 0; i < in.n_points; ++i) {
      if (i % silk::kCancelPollInterval == 0 && silk::CancelRequested(cancel))
        return silk::CancelledStatus("input conversion");
      for (int a = 0; a < 3; ++a) {
        out.mesh.positions[i][a] = in.points[6 * i + a];
        out.normals[i][a] = in.points[6 * i + 3 + a];
      }
    }
  }
  SILK_RETURN_IF_ERROR(silk::ValidateGenerationInput(out, cancel));
  return out;
}

// Prepares the encoder's points: raw ones as given (RawModelPoints), else the model's
// pre-processing (model.json "preprocessing", or the kind the params name).
silk::Status PreparePoints(silk_generator* g, const silk::GenerationInput& in, const silk_generate_params& p,
                           const silk::CancelCheck& cancel) {
  const silk::ModelConfig& cfg = g->model->config();
  silk::PreprocessingParams prep = silk::ModelPreprocessing(cfg, p.n_points);
  if (p.preprocessing >= 0 && p.preprocessing != static_cast<int32_t>(prep.kind))
    prep = p.preprocessing == SILK_PREPROCESS_OFFICIAL ? silk::OfficialPreprocessing(prep.n_points)
                                                       : silk::SilkPreprocessing(prep.normalize_bound, prep.n_points);
  SILK_ASSIGN_OR_RETURN(silk::PreparedPoints pts, p.raw_points ? silk::RawModelPoints(in, cfg.dims.n_points)
                                                               : silk::PrepareModelPoints(in, prep, p.seed, cancel));
  g->points = std::move(pts.rows);
  g->transform = pts.transform;
  g->settings.preprocessing = p.raw_points ? "raw" : silk::PreprocessingKindName(prep.kind);
  return silk::Status::Ok();
}

// Checks the params and input, records the settings and prepares the encoder's points; what
// starts a generation (step-wise or best of N) comes after. The run's cancel flag was cleared
// as the call took the generator (BusyLock), so a cancel from then on is never lost.
silk_status Prepare(silk_generator* g, const silk_generate_input& input, const silk_generate_params& p,
                    silk::GenerateOptions* options_out) {
  const silk::GenerateCallbacks cb = ToCallbacks(g, p);
  if (cb.cancel()) {  // the call's first poll, before the (long) input conversion
    g->has_result = false;
    return SetError(SILK_ERR_CANCELLED, "generation cancelled");
  }
  auto options = ToOptions(p, g->model->config());
  if (!options.ok()) return SetError(options.status().WithContext("silk_generator_start: "));
  // Input problems name the input's file when it came from one.
  const std::string context = input.mesh && !input.mesh->source.empty() ? input.mesh->source + ": " : "input: ";
  auto in = ToInput(input, FlagCheck(g));
  if (!in.ok()) return SetError(in.status().WithContext(context));
  g->has_result = false;
  GenerationSettings& s = g->settings;
  s = GenerationSettings{};
  s.input_name = input.mesh ? (input.mesh->source.empty() ? "mesh" : input.mesh->source) : "points";
  s.point_cloud = in->point_cloud;
  s.raw = p.raw_points != 0;
  s.input_vertices = static_cast<int32_t>(in->mesh.positions.size());
  s.input_faces = static_cast<int32_t>(in->mesh.triangles.size());
  s.params = p;
  s.options = *options;
  const auto t0 = Clock::now();
  if (silk::Status st = PreparePoints(g, *in, p, cb.cancel); !st.ok())
    return SetError(st.WithContext(context));
  g->prepare_seconds = std::chrono::duration<double>(Clock::now() - t0).count();
  s.points = static_cast<int32_t>(g->points.size() / 6);
  *options_out = *options;
  return Ok();
}

// Step-wise start: one generation (candidate 0; `candidates` is for silk_generate*).
silk_status Start(silk_generator* g, const silk_generate_input& input, const silk_generate_params& p) {
  silk::GenerateOptions options;
  if (silk_status s = Prepare(g, input, p, &options); s != SILK_OK) return s;
  return SetError(g->generator.Start(g->points, options, ToCallbacks(g, p)));
}

silk_status Advance(silk_generator* g, int32_t max_ids, int32_t until) {
  const int64_t layers = g->generator.layers_closed();
  for (int32_t i = 0; i < max_ids && !g->generator.finished(); ++i) {
    if (silk::Status st = g->generator.Step(); !st.ok()) return SetError(st);
    if (until == SILK_ADVANCE_LAYER && g->generator.layers_closed() > layers) break;
  }
  return Ok();
}

// A finished generation (one, or the best of N) as the caller's mesh in the input frame,
// verdicts and figures.
silk_status Deliver(silk_generator* g, silk::GenerateResult result, silk_mesh** out_mesh, silk_tokens** out_tokens,
                    silk_generate_stats* stats) {
  g->result = std::move(result);
  silk::IoMesh output = silk::FinishOutput(&g->result, g->transform);  // verdicts into the stats
  silk::GenerationStats& st = g->result.stats;
  st.seconds.load_input += g->prepare_seconds;
  st.seconds.total = st.seconds.load_input + st.generation_seconds + st.seconds.build_mesh + st.seconds.scoring;
  g->has_result = true;
  auto mesh = silk::capi::MeshHandle(std::move(output.positions), g->result.mesh);
  std::unique_ptr<silk_tokens> tokens;
  if (out_tokens) {
    tokens = std::make_unique<silk_tokens>();
    tokens->ids = g->result.tokens;
  }
  if (stats) silk::capi::FillStats(st, stats);
  silk::capi::Log(SILK_LOG_DEBUG, "generated " + std::to_string(st.tokens) + " ids (" + st.stop_reason + ") -> " +
                                      std::to_string(st.faces) + " faces");
  *out_mesh = mesh.release();
  if (out_tokens) *out_tokens = tokens.release();
  return Ok();
}

// A cancelled one-call run: stats of the generation (`st`, or the one in progress), which is
// released unscored; its mesh is not returned and there is no report of it.
silk_status Cancelled(silk_generator* g, silk_generate_stats* stats, const silk::GenerationStats* st = nullptr) {
  const std::string message = silk_last_error();
  if (stats) {
    silk::capi::FillStats(st ? *st : g->generator.stats(), stats);
    stats->stop_reason = SILK_STOP_CANCELLED;
  }
  if (g->generator.active()) {
    auto r = g->generator.Finish();
    if (r.ok()) g->result = std::move(*r);
  }
  g->has_result = false;
  return SetError(SILK_ERR_CANCELLED, message);
}

// Finishes the generation and scores it (its single candidate entry); `scoring` (one-call runs)
// may stop the scoring: then the run is cancelled.
silk_status Finish(silk_generator* g, silk_mesh** out_mesh, silk_tokens** out_tokens, silk_generate_stats* stats,
                   const silk::CancelCheck& scoring = {}) {
  auto r = g->generator.Finish();
  if (!r.ok()) return SetError(r.status());
  if (silk::Status st = silk::ScoreSingle(&*r, g->settings.options.sampling.seed, g->points, scoring); !st.ok()) {
    SetError(st);
    g->result = std::move(*r);
    return Cancelled(g, stats, &g->result.stats);
  }
  return Deliver(g, std::move(*r), out_mesh, out_tokens, stats);
}

// A one-call run cancelled after its last poll (while its output was built): the output is
// dropped, as if the cancel had come a moment earlier.
silk_status DropOutput(silk_generator* g, silk_mesh** out_mesh, silk_tokens** out_tokens, silk_generate_stats* stats) {
  delete *out_mesh;
  *out_mesh = nullptr;
  if (out_tokens) {
    delete *out_tokens;
    *out_tokens = nullptr;
  }
  if (stats) stats->stop_reason = SILK_STOP_CANCELLED;
  g->has_result = false;
  return SetError(SILK_ERR_CANCELLED, "generation cancelled");
}

// Best of N (candidates > 1): every candidate on the one generator, the closest returned.
silk_status RunBest(silk_generator* g, const silk_generate_input& input, const silk_generate_params& p,
                    silk_mesh** out_mesh, silk_tokens** out_tokens, silk_generate_stats* stats) {
  silk::GenerateOptions options;
  if (silk_status s = Prepare(g, input, p, &options); s != SILK_OK) return s;
  auto r = silk::RunCandidates(&g->generator, g->points, options, ToCallbacks(g, p), FlagCheck(g));
  if (!r.ok()) {
    const silk_status s = SetError(r.status());
    return s == SILK_ERR_CANCELLED ? Cancelled(g, stats) : s;
  }
  return Deliver(g, std::move(*r), out_mesh, out_tokens, stats);
}

// start + advance to the end + finish; a cancel still fills the stats.
silk_status RunAll(silk_generator* g, const silk_generate_input& input, const silk_generate_params* params,
                   silk_mesh** out_mesh, silk_tokens** out_tokens, silk_generate_stats* stats) {
  const silk_generate_params p = params ? *params : silk_generate_default_params();
  if (stats) std::memset(stats, 0, sizeof(*stats));
  if (ResolvedCandidates(p, g->model->config()) > 1) return RunBest(g, input, p, out_mesh, out_tokens, stats);
  silk_status s = Start(g, input, p);
  if (s == SILK_OK) s = Advance(g, INT32_MAX, SILK_ADVANCE_IDS);
  if (s == SILK_ERR_CANCELLED) return Cancelled(g, stats);
  if (s != SILK_OK) return s;
  return Finish(g, out_mesh, out_tokens, stats, FlagCheck(g));
}

}  // namespace

extern "C" {

silk_generate_params silk_generate_default_params(void) {
  silk_generate_params p;
  std::memset(&p, 0, sizeof(p));
  p.seed = 0;
  p.temperature = SILK_MODEL_VALUE;  // the model's (model.json "sampling")
  p.top_k = SILK_MODEL_VALUE;
  p.top_p = SILK_MODEL_VALUE;
  p.top_p_temperature = SILK_MODEL_VALUE;
  p.preprocessing = SILK_MODEL_VALUE;  // the model's (model.json "preprocessing")
  p.holes = SILK_HOLES_OFF;
  p.surface_tolerance = SILK_DEFAULT_SURFACE_TOLERANCE;
  p.candidates = SILK_DEFAULT_CANDIDATES;
  p.orient = SILK_DEFAULT_ORIENT;
  return p;
}

silk_status silk_generator_create(const silk_model* model, silk_generator** out) {
  return Guard([&] {
    SILK_CAPI_REQUIRE(out, "silk_generator_create: out is NULL");
    *out = nullptr;
    SILK_CAPI_REQUIRE(model, "silk_generator_create: model is NULL");
    *out = new silk_generator(model->model);
    return Ok();
  });
}

void silk_generator_destroy(silk_generator* generator) {
  if (!generator || silk::capi::DeferDestroy(generator)) return;  // deferred: the call inside frees it
  delete generator;
}

silk_status silk_generator_start(silk_generator* g, const silk_generate_input* input, const silk_generate_params* params) {
  return Guard([&] {
    SILK_CAPI_REQUIRE(g && input, "silk_generator_start: generator or input is NULL");
    BusyLock lock(g, BusyLock::kBegin);
    if (!lock.ok()) return Busy("silk_generator_start");
    const silk_status s = Start(g, *input, params ? *params : silk_generate_default_params());
    if (s == SILK_OK) lock.KeepRun();  // the run goes on until finish (a cancel now is for it)
    return s;
  });
}

silk_status silk_generator_advance(silk_generator* g, int32_t max_ids, int32_t until, int32_t* out_done) {
  return Guard([&] {
    if (out_done) *out_done = 0;
    SILK_CAPI_REQUIRE(g, "silk_generator_advance: generator is NULL");
    SILK_CAPI_REQUIRE(max_ids >= 1, "silk_generator_advance: max_ids must be at least 1");
    SILK_CAPI_REQUIRE(until == SILK_ADVANCE_IDS || until == SILK_ADVANCE_LAYER,
                      "silk_generator_advance: until is not a silk_advance_until (0..1)");
    BusyLock lock(g);
    if (!lock.ok()) return Busy("silk_generator_advance");
    if (!g->generator.active()) return SetError(SILK_ERR_INVALID_ARGUMENT, "silk_generator_advance: no generation started");
    const silk_status s = Advance(g, max_ids, until);
    if (out_done) *out_done = g->generator.finished() ? 1 : 0;
    return s;
  });
}

void silk_generator_cancel(silk_generator* g) {
  if (g) silk::capi::CancelRun(g);  // flag first: Start polls it after clearing the terminate flag
}

silk_status silk_generator_tokens(silk_generator* g, silk_tokens** out) {
  return Guard([&] {
    SILK_CAPI_REQUIRE(g && out, "silk_generator_tokens: NULL argument");
    *out = nullptr;
    BusyLock lock(g);
    if (!lock.ok()) return Busy("silk_generator_tokens");
    auto t = std::make_unique<silk_tokens>();
    t->ids = g->generator.active() ? g->generator.tokens() : g->result.tokens;
    *out = t.release();
    return Ok();
  });
}

silk_status silk_generator_mesh(silk_generator* g, silk_mesh** out) {
  return Guard([&] {
    SILK_CAPI_REQUIRE(g && out, "silk_generator_mesh: NULL argument");
    *out = nullptr;
    BusyLock lock(g);
    if (!lock.ok()) return Busy("silk_generator_mesh");
    if (!g->generator.active()) return SetError(SILK_ERR_INVALID_ARGUMENT, "silk_generator_mesh: no generation in progress");
    auto so_far = g->generator.MeshSoFar();
    if (!so_far.ok()) return SetError(so_far.status());
    auto h = silk::capi::MeshHandle(silk::ToInputFrame(*so_far, g->transform).positions, *so_far);
    *out = h.release();
    return Ok();
  });
}

silk_status silk_generator_stats(silk_generator* g, silk_generate_stats* out) {
  return Guard([&] {
    SILK_CAPI_REQUIRE(g && out, "silk_generator_stats: NULL argument");
    BusyLock lock(g);
    if (!lock.ok()) return Busy("silk_generator_stats");
    if (!g->generator.active()) {
      silk::capi::FillStats(g->result.stats, out);
      return Ok();
    }
    silk::capi::FillStats(g->generator.stats(), out);
    auto so_far = g->generator.MeshSoFar();
    if (so_far.ok()) {
      out->faces = static_cast<int32_t>(so_far->faces.size());
      out->vertices = static_cast<int32_t>(so_far->positions.size());
      out->components = so_far->components;
    }
    return Ok();
  });
}

silk_status silk_generator_finish(silk_generator* g, silk_mesh** out_mesh, silk_tokens** out_tokens,
                                  silk_generate_stats* stats) {
  return Guard([&] {
    SILK_CAPI_REQUIRE(out_mesh, "silk_generator_finish: out_mesh is NULL");
    *out_mesh = nullptr;
    if (out_tokens) *out_tokens = nullptr;
    SILK_CAPI_REQUIRE(g, "silk_generator_finish: generator is NULL");
    BusyLock lock(g, BusyLock::kEnd);
    if (!lock.ok()) return Busy("silk_generator_finish");
    if (!g->generator.active()) return SetError(SILK_ERR_INVALID_ARGUMENT, "silk_generator_finish: no generation started");
    return Finish(g, out_mesh, out_tokens, stats);
  });
}

silk_status silk_generator_report(silk_generator* g, int32_t trace, silk_report** out) {
  return Guard([&] {
    SILK_CAPI_REQUIRE(out, "silk_generator_report: out is NULL");
    *out = nullptr;
    SILK_CAPI_REQUIRE(g, "silk_generator_report: generator is NULL");
    SILK_CAPI_REQUIRE(trace == 0 || trace == 1, "silk_generator_report: trace takes 0 or 1");
    BusyLock lock(g);
    if (!lock.ok()) return Busy("silk_generator_report");
    if (!g->has_result) return SetError(SILK_ERR_INVALID_ARGUMENT, "silk_generator_report: no finished generation");
    if (trace && !(g->settings.params.debug_flags & SILK_DEBUG_RECORD_TRACE))
      return SetError(SILK_ERR_INVALID_ARGUMENT, "silk_generator_report: the generation ran without SILK_DEBUG_RECORD_TRACE");
    auto r = std::make_unique<silk_report>();
    r->json = silk::capi::ReportJson(*g, trace != 0);
    *out = r.release();
    return Ok();
  });
}

silk_status silk_generate_input_run(silk_generator* g, const silk_generate_input* input, const silk_generate_params* params,
                                    silk_mesh** out_mesh, silk_tokens** out_tokens, silk_generate_stats* stats) {
  return Guard([&] {
    SILK_CAPI_REQUIRE(out_mesh, "silk_generate: out_mesh is NULL");
    *out_mesh = nullptr;
    if (out_tokens) *out_tokens = nullptr;
    SILK_CAPI_REQUIRE(g && input, "silk_generate: generator or input is NULL");
    BusyLock lock(g, BusyLock::kWhole);  // the run, and its cancel flag, begin here
    if (!lock.ok()) return Busy("silk_generate");
    const silk_status s = RunAll(g, *input, params, out_mesh, out_tokens, stats);
    // The run ends here: a cancel that came before is honoured even if no poll was left to see it.
    if (lock.EndRun() && s == SILK_OK) return DropOutput(g, out_mesh, out_tokens, stats);
    return s;
  });
}

silk_status silk_generate(silk_generator* g, const silk_mesh* mesh, const silk_generate_params* params,
                          silk_mesh** out_mesh, silk_tokens** out_tokens, silk_generate_stats* stats) {
  if (!mesh) {
    if (out_mesh) *out_mesh = nullptr;
    return SetError(SILK_ERR_INVALID_ARGUMENT, "silk_generate: generator or mesh is NULL");
  }
  silk_generate_input in{};
  in.mesh = mesh;
  return silk_generate_input_run(g, &in, params, out_mesh, out_tokens, stats);
}

silk_status silk_generate_from_points(silk_generator* g, const double* points, size_t n_points,
                                      const silk_generate_params* params, silk_mesh** out_mesh,
                                      silk_tokens** out_tokens, silk_generate_stats* stats) {
  if (!points || n_points == 0) {
    if (out_mesh) *out_mesh = nullptr;
    return SetError(SILK_ERR_INVALID_ARGUMENT, "silk_generate_from_points: no generator or no points");
  }
  silk_generate_input in{};
  in.points = points;
  in.n_points = n_points;
  return silk_generate_input_run(g, &in, params, out_mesh, out_tokens, stats);
}

}  // extern "C"
#endif
