// SPDX-License-Identifier: MIT
// The one JSON report of a generation (silkgen --stats/--trace, silk_generator_report) and
// the one mapping of GenerationStats onto silk_generate_stats. nlohmann::ordered_json keeps the
// keys in a readable order; trace floats have 9 significant digits so float32 reads back exactly.
// Non-finite figures are null: nlohmann dumps NaN / Inf as null, JsonNumber likewise.
#if defined(SILK_HAVE_RUNTIME)
#include <cmath>
#include <cstring>

#include <nlohmann/json.hpp>

#include "capi/capi_generator.h"
#include "core/json_number.h"
#include "runtime/model/model_config.h"

namespace silk::capi {

namespace {

using Json = nlohmann::ordered_json;

Json SettingsJson(const silk_generator& g) {
  const silk_generate_params& p = g.settings.params;
  const GenerationPlan& plan = g.session.plan();  // resolved: model.json defaults applied
  const SamplingParams& sp = plan.options.sampling;
  return Json{{"input", g.settings.input_name},
              {"model", g.model->config().dir},
              {"model_config", g.model->config().config_name},
              {"point_cloud_input", g.settings.point_cloud},
              {"seed", sp.seed},
              {"temperature", sp.temperature},
              {"top_k", sp.top_k},
              {"top_p", sp.top_p},
              {"top_p_temperature", sp.top_p_temperature},
              {"preprocessing", plan.preprocessing_name()},
              {"max_tokens", p.max_tokens},
              {"max_faces", p.max_faces},
              {"repair", silk_hole_policy_name(p.holes)},
              {"unconstrained", g.settings.unconstrained},
              {"surface_tolerance", p.surface_tolerance},
              {"candidates", plan.options.candidates},  // resolved: the model's N applied
              {"rows", plan.options.rows},              // resolved: the model's, else libsilk's
              {"orient", silk_orientation_name(p.orient)},
              {"face_guidance", FaceGuidanceName(plan.options.face_guidance)},  // resolved: the model's applied
              {"face_tolerance", plan.options.face_tolerance}};
}

Json StatsJson(const silk_generator& g) {
  const GenerationStats& st = g.result.stats;
  Json j;
  j["settings"] = SettingsJson(g);
  j["input"] = {{"vertices", g.settings.input_vertices},
                {"faces", g.settings.input_faces},
                {"points", g.session.points().size() / 6}};
  j["tokens"] = st.tokens;
  j["stop_reason"] = StopReasonName(st.stop_reason);
  if (!st.dead_end.empty()) j["grammar_dead_end"] = st.dead_end;
  j["faces"] = st.faces;
  j["vertices"] = st.vertices;
  j["components"] = st.components;
  j["forced_tokens"] = st.forced_tokens;
  j["forced_share"] = st.forced_share();
  j["sampled_tokens"] = st.sampled_tokens;
  j["model_calls"] = st.model_calls;
  j["tokens_per_second"] = st.tokens_per_second;
  j["threads"] = st.threads;
  j["int8"] = st.int8;
  j["decoder"] = st.decoder;
  j["kv_precision"] = st.kv_precision;
  j["kv_cache_bytes"] = st.kv_cache_bytes;
  j["model_version"] = st.model_version;
  j["decoder_contract"] = st.decoder_contract;
  const std::string note = silk::ModelVersionNote(st.model_version);
  if (!note.empty()) j["model_version_note"] = note;
  j["seconds"] = {
      {"load_input", st.seconds.load_input}, {"encoder", st.seconds.encoder},   {"decoder", st.seconds.decoder},
      {"grammar", st.seconds.grammar},       {"sampling", st.seconds.sampling}, {"build_mesh", st.seconds.build_mesh},
      {"guidance", st.seconds.guidance},     {"scoring", st.seconds.scoring},   {"total", st.seconds.total}};
  j["repairs"] = {{"holes_found", st.holes_found},         {"holes_repaired", st.holes_repaired},
                  {"faces_added", st.faces_added},         {"window_findings", st.window_findings},
                  {"fan_gaps_closed", st.fan_gaps_closed}, {"vertices_split", st.vertices_split}};
  j["verdicts"] = {{"edge_manifold", st.edge_manifold},
                   {"vertex_manifold", st.vertex_manifold},
                   {"nonmanifold_vertices", st.nonmanifold_vertices},
                   {"watertight", st.watertight},
                   {"consistently_oriented", st.consistently_oriented},
                   {"open_edges", st.open_edges}};
  j["guidance"] = {
      {"guided_tokens", st.guided_tokens}, {"fallbacks", st.guidance_fallbacks}, {"seconds", st.seconds.guidance}};
  j["face_guidance"] = {{"guided_tokens", st.face_guided_tokens},
                        {"fallbacks", st.face_fallbacks},
                        {"seconds", st.seconds.face_guidance}};
  j["parts_flipped"] = st.parts_flipped;
  Json cands = Json::array();
  for (size_t i = 0; i < st.candidates.size(); ++i) {
    const CandidateScore& c = st.candidates[i];
    cands.push_back({{"index", i},
                     {"seed", c.seed},
                     {"score", std::isfinite(c.score) ? Json(c.score) : Json(nullptr)},
                     {"faces", c.faces},
                     {"tokens", c.tokens},
                     {"seconds", c.seconds}});
  }
  j["candidates"] = cands;
  j["chosen_candidate"] = st.chosen_candidate;
  j["rows"] = st.rows;  // best of N's rows used: min(settings.rows, candidates)
  if (g.settings.unconstrained) j["grammar"] = {{"first_illegal_token", st.illegal_at}, {"reason", st.illegal_reason}};
  return j;
}

Json TraceJson(const silk_generator& g) {
  Json j;
  j["settings"] = SettingsJson(g);
  // The seed the traced ids were sampled with: the chosen candidate's (candidate 0: the seed).
  const GenerationStats& st = g.result.stats;
  if (!st.candidates.empty()) j["settings"]["seed"] = st.candidates[static_cast<size_t>(st.chosen_candidate)].seed;
  std::string pts = "[";
  const std::vector<float>& points = g.session.points();
  for (size_t i = 0; i < points.size(); ++i)
    pts += (i ? "," : "") + JsonNumber(static_cast<double>(points[i]), 9);  // null, never nan/inf
  pts += "]";
  j["points"] = Json::parse(pts);
  j["tokens"] = g.result.tokens;
  Json steps = Json::array();
  for (const TraceStep& s : g.result.trace) {
    Json legal = Json::array();
    for (const auto& [b, e] : s.legal) legal.push_back({b, e});
    Json step = {{"id", s.id}, {"forced", s.forced}, {"legal", legal}};
    if (!s.penalties.empty()) {  // soft face guidance: floats as doubles, so they read back exactly
      Json pen = Json::array();
      for (const auto& [id, amount] : s.penalties) pen.push_back({id, static_cast<double>(amount)});
      step["penalties"] = pen;
    }
    if (s.face != FaceVerdict::kNotJudged) step["face"] = s.face == FaceVerdict::kFallback ? "fallback" : "passed";
    steps.push_back(step);
  }
  j["steps"] = steps;
  return j;
}

}  // namespace

std::string ReportJson(const silk_generator& g, bool trace) {
  return trace ? TraceJson(g).dump() + "\n" : StatsJson(g).dump(2) + "\n";
}

// StopReason is silk_stop_reason value for value (silk_stop_reason_name relies on it too).
static_assert(static_cast<int32_t>(StopReason::kNone) == SILK_STOP_NONE &&
              static_cast<int32_t>(StopReason::kEos) == SILK_STOP_EOS &&
              static_cast<int32_t>(StopReason::kMaxTokens) == SILK_STOP_MAX_TOKENS &&
              static_cast<int32_t>(StopReason::kMaxFaces) == SILK_STOP_MAX_FACES &&
              static_cast<int32_t>(StopReason::kGrammarDeadEnd) == SILK_STOP_GRAMMAR_DEAD_END &&
              static_cast<int32_t>(StopReason::kCancelled) == SILK_STOP_CANCELLED);

void FillStats(const GenerationStats& s, silk_generate_stats* out) {
  *out = Blank<silk_generate_stats>();
  out->tokens = s.tokens;
  out->forced_tokens = s.forced_tokens;
  out->sampled_tokens = s.sampled_tokens;
  out->model_calls = s.model_calls;
  out->stop_reason = static_cast<int32_t>(s.stop_reason);
  out->faces = s.faces;
  out->vertices = s.vertices;
  out->components = s.components;
  out->holes_found = s.holes_found;
  out->holes_repaired = s.holes_repaired;
  out->faces_added = s.faces_added;
  out->edge_manifold = s.edge_manifold;
  out->watertight = s.watertight;
  out->consistently_oriented = s.consistently_oriented;
  out->open_edges = s.open_edges;
  out->illegal_at = s.illegal_at;
  out->tokens_per_second = s.tokens_per_second;
  out->seconds_prepare = s.seconds.load_input;
  out->seconds_encoder = s.seconds.encoder;
  out->seconds_decoder = s.seconds.decoder;
  out->seconds_grammar = s.seconds.grammar;
  out->seconds_sampling = s.seconds.sampling;
  out->seconds_build_mesh = s.seconds.build_mesh;
  out->seconds_total = s.seconds.total;
  out->vertex_manifold = s.vertex_manifold;
  out->nonmanifold_vertices = s.nonmanifold_vertices;
  out->fan_gaps_closed = s.fan_gaps_closed;
  out->vertices_split = s.vertices_split;
  out->guided_tokens = s.guided_tokens;
  out->guidance_fallbacks = s.guidance_fallbacks;
  out->candidates = static_cast<int32_t>(s.candidates.size());
  out->chosen_candidate = s.chosen_candidate;
  out->score = s.candidates.empty() ? 0 : s.candidates[static_cast<size_t>(s.chosen_candidate)].score;
  out->seconds_guidance = s.seconds.guidance;
  out->face_guided_tokens = s.face_guided_tokens;
  out->face_fallbacks = s.face_fallbacks;
  out->seconds_face_guidance = s.seconds.face_guidance;
  out->seconds_scoring = s.seconds.scoring;
  out->parts_flipped = s.parts_flipped;
  out->rows = s.rows;
}

}  // namespace silk::capi
#endif
