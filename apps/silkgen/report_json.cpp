// nlohmann::ordered_json keeps the keys in a readable order; floats of the trace are written
// with 9 significant digits so float32 values read back exactly.
#include "report_json.h"

#include <cstdio>

#include <nlohmann/json.hpp>

namespace silkgen {

namespace {

using Json = nlohmann::ordered_json;

const char* HolesName(silk::HolePolicy h) {
  switch (h) {
    case silk::HolePolicy::kOff: return "off";
    case silk::HolePolicy::kReport: return "report";
    case silk::HolePolicy::kRepair: return "repair";
  }
  return "?";
}

Json SettingsJson(const RunSettings& s) {
  const auto& o = s.options;
  return Json{{"input", s.input},
              {"output", s.output},
              {"model", s.model_dir},
              {"model_config", s.model_config},
              {"point_cloud_input", s.point_cloud},
              {"seed", o.sampling.seed},
              {"temperature", o.sampling.temperature},
              {"top_k", o.sampling.top_k},
              {"top_p", o.sampling.top_p},
              {"top_p_temperature", o.sampling.top_p_temperature},
              {"preprocessing", s.preprocessing},
              {"max_tokens", o.max_tokens},
              {"max_faces", o.max_faces},
              {"repair", HolesName(o.holes)},
              {"unconstrained", o.unconstrained}};
}

}  // namespace

std::string StatsJson(const RunSettings& settings, const silk::PipelineResult& r) {
  const silk::GenerationStats& st = r.generation.stats;
  Json j;
  j["settings"] = SettingsJson(settings);
  j["input"] = {{"vertices", settings.input_vertices}, {"faces", settings.input_faces}, {"points", settings.points}};
  j["tokens"] = st.tokens;
  j["stop_reason"] = st.stop_reason;
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
  j["kv_cache_bytes"] = st.kv_cache_bytes;
  j["seconds"] = {{"load_input", st.seconds.load_input}, {"encoder", st.seconds.encoder},
                  {"decoder", st.seconds.decoder},       {"grammar", st.seconds.grammar},
                  {"sampling", st.seconds.sampling},     {"build_mesh", st.seconds.build_mesh},
                  {"write_output", st.seconds.write_output}, {"total", st.seconds.total}};
  j["repairs"] = {{"holes_found", st.holes_found}, {"holes_repaired", st.holes_repaired},
                  {"faces_added", st.faces_added}, {"window_findings", st.window_findings},
                  {"fan_gaps_closed", st.fan_gaps_closed}, {"vertices_split", st.vertices_split}};
  j["verdicts"] = {{"edge_manifold", st.edge_manifold}, {"vertex_manifold", st.vertex_manifold},
                   {"nonmanifold_vertices", st.nonmanifold_vertices}, {"watertight", st.watertight},
                   {"consistently_oriented", st.consistently_oriented}, {"open_edges", st.open_edges}};
  if (settings.options.unconstrained)
    j["grammar"] = {{"first_illegal_token", st.illegal_at}, {"reason", st.illegal_reason}};
  return j.dump(2) + "\n";
}

std::string TraceJson(const RunSettings& settings, const std::vector<float>& points, const silk::GenerateResult& gen) {
  Json j;
  j["settings"] = SettingsJson(settings);
  std::string pts = "[";
  char buf[32];
  for (size_t i = 0; i < points.size(); ++i) {
    std::snprintf(buf, sizeof(buf), "%s%.9g", i ? "," : "", static_cast<double>(points[i]));
    pts += buf;
  }
  pts += "]";
  j["points"] = Json::parse(pts);
  j["tokens"] = gen.tokens;
  Json steps = Json::array();
  for (const silk::TraceStep& s : gen.trace) {
    Json legal = Json::array();
    for (const auto& [b, e] : s.legal) legal.push_back({b, e});
    steps.push_back({{"id", s.id}, {"forced", s.forced}, {"legal", legal}});
  }
  j["steps"] = steps;
  return j.dump() + "\n";
}

}  // namespace silkgen
