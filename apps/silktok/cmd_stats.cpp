// SPDX-License-Identifier: MIT
// `silktok stats`: encode a mesh and report what the tokenizer did — counts, layers,
// tokens per face, bits per face, structure limits, time per phase.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>

#include "../common/app_files.h"
#include "commands.h"
#include "mesh_input.h"

namespace silktok {
namespace {

struct StatsArgs {
  std::string input;
  bool json = false;
  bool no_nonmanifold = false;
};

nlohmann::json StatsJson(const std::string& path, const silk_encode_stats& s, double total_s) {
  const silk_vocab_info v = silk_cpp::Vocab();
  const double faces = std::max(1, s.processed_faces);
  const double bits_per_token = std::log2(static_cast<double>(v.format_vocab_size));
  nlohmann::json j;
  j["file"] = path;
  j["input"] = {{"vertices", s.input_vertices}, {"faces", s.input_faces}};
  j["cleanup"] = {{"merged_vertices", s.merged_vertices},
                  {"degenerate_faces_dropped", s.dropped_degenerate_faces},
                  {"duplicate_faces_dropped", s.dropped_duplicate_faces},
                  {"nonmanifold_vertex_copies", s.nonmanifold_copies},
                  {"faces_flipped", s.flipped_faces}};
  j["processed"] = {{"vertices", s.processed_vertices},
                    {"faces", s.processed_faces},
                    {"emitted_vertices", s.emitted_vertices},
                    {"encodable_faces", s.encodable_faces},
                    {"unencodable_faces", s.processed_faces - s.encodable_faces},
                    {"unreached_vertices", s.processed_vertices - s.emitted_vertices}};
  j["components"] = {{"found", s.components_found},
                     {"encoded", s.components_encoded},
                     {"dropped", s.components_found - s.components_encoded},
                     {"dropped_reason", "fewer than 3 faces"}};
  j["layers"] = {
      {"total", s.layers}, {"max_layer_size", s.max_layer_size}, {"max_layers_per_component", s.max_layer_count}};
  j["tokens"] = {{"count", s.tokens},
                 {"tokens_per_face", s.tokens / faces},
                 {"bits_per_face", s.tokens * bits_per_token / faces},
                 {"compression_ratio", s.tokens / (9.0 * faces)}};
  j["limits"] = {{"layer_size", {{"value", s.max_layer_size}, {"limit", v.layer_vertex_limit}}},
                 {"layer_count", {{"value", s.max_layer_count}, {"limit", v.layer_count_limit}}},
                 {"faces", {{"value", s.processed_faces}, {"limit", v.max_faces}}},
                 {"model_sequence",
                  {{"value", s.tokens + 1}, {"limit", v.max_seq_length}, {"fits", s.tokens + 1 <= v.max_seq_length}}}};
  j["time_s"] = {{"quantize_cleanup", s.seconds_quantize_cleanup},
                 {"nonmanifold", s.seconds_nonmanifold},
                 {"orientation", s.seconds_orientation},
                 {"components", s.seconds_components},
                 {"layering", s.seconds_layering},
                 {"codecs", s.seconds_codecs},
                 {"packing", s.seconds_packing},
                 {"total_with_io", total_s}};
  return j;
}

void PrintText(const nlohmann::json& j) {
  std::printf("file                 %s\n", j["file"].get<std::string>().c_str());
  std::printf("input                %d vertices, %d faces\n", j["input"]["vertices"].get<int>(),
              j["input"]["faces"].get<int>());
  const auto& c = j["cleanup"];
  std::printf(
      "cleanup              %d merged vertices, %d degenerate + %d duplicate faces dropped, "
      "%d non-manifold copies, %d faces flipped\n",
      c["merged_vertices"].get<int>(), c["degenerate_faces_dropped"].get<int>(),
      c["duplicate_faces_dropped"].get<int>(), c["nonmanifold_vertex_copies"].get<int>(),
      c["faces_flipped"].get<int>());
  const auto& p = j["processed"];
  std::printf("processed            %d vertices, %d faces (%d encodable, %d unencodable; %d vertices unreached)\n",
              p["vertices"].get<int>(), p["faces"].get<int>(), p["encodable_faces"].get<int>(),
              p["unencodable_faces"].get<int>(), p["unreached_vertices"].get<int>());
  const auto& k = j["components"];
  std::printf("components           %d found, %d encoded, %d dropped (fewer than 3 faces)\n", k["found"].get<int>(),
              k["encoded"].get<int>(), k["dropped"].get<int>());
  const auto& l = j["layers"];
  std::printf("layers               %d total, max layer size %d, max %d layers in a component\n", l["total"].get<int>(),
              l["max_layer_size"].get<int>(), l["max_layers_per_component"].get<int>());
  const auto& t = j["tokens"];
  std::printf("tokens               %lld (%.3f tokens/face, %.2f bits/face, compression ratio %.3f)\n",
              static_cast<long long>(t["count"].get<int64_t>()), t["tokens_per_face"].get<double>(),
              t["bits_per_face"].get<double>(), t["compression_ratio"].get<double>());
  std::printf("limits               layer size %d/%d, layers %d/%d, faces %d/%d, model sequence %lld/%d%s\n",
              j["limits"]["layer_size"]["value"].get<int>(), j["limits"]["layer_size"]["limit"].get<int>(),
              j["limits"]["layer_count"]["value"].get<int>(), j["limits"]["layer_count"]["limit"].get<int>(),
              j["limits"]["faces"]["value"].get<int>(), j["limits"]["faces"]["limit"].get<int>(),
              static_cast<long long>(j["limits"]["model_sequence"]["value"].get<int64_t>()),
              j["limits"]["model_sequence"]["limit"].get<int>(),
              j["limits"]["model_sequence"]["fits"].get<bool>() ? "" : " (TOO LONG for the model)");
  const auto& tm = j["time_s"];
  std::printf(
      "time (ms)            cleanup %.2f, non-manifold %.2f, orientation %.2f, components %.2f, "
      "layering %.2f, codecs %.2f, packing %.2f; total with I/O %.2f\n",
      1e3 * tm["quantize_cleanup"].get<double>(), 1e3 * tm["nonmanifold"].get<double>(),
      1e3 * tm["orientation"].get<double>(), 1e3 * tm["components"].get<double>(), 1e3 * tm["layering"].get<double>(),
      1e3 * tm["codecs"].get<double>(), 1e3 * tm["packing"].get<double>(), 1e3 * tm["total_with_io"].get<double>());
}

int Run(const StatsArgs& a) {
  const auto t0 = std::chrono::steady_clock::now();
  silk_encode_params params = silk_encode_default_params();
  params.nonmanifold_processing = a.no_nonmanifold ? 0 : 1;
  silk_encode_stats stats = silk_cpp::Sized<silk_encode_stats>();
  try {
    LoadAndEncode(a.input, params, &stats);
  } catch (const silk_cpp::Error& e) {
    ReportError(e);
    if (a.json) {
      nlohmann::json j{{"file", a.input}, {"error", e.what()}};
      std::printf("%s\n", j.dump(2).c_str());
    }
    return kExitFailure;
  }
  const double total = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const nlohmann::json j = StatsJson(a.input, stats, total);
  if (a.json)
    std::printf("%s\n", j.dump(2).c_str());
  else
    PrintText(j);
  return kExitOk;
}

}  // namespace

void RegisterStatsCommand(CLI::App& app) {
  auto args = std::make_shared<StatsArgs>();
  CLI::App* cmd = app.add_subcommand(
      "stats",
      "Encode a mesh and report faces, vertices, components (found / encoded / dropped and why), layers,\n"
      "max layer size, tokens, tokens/face, bits/face (tokens x log2(10267) / faces), compression ratio\n"
      "(tokens / (9 x faces), the paper's measure), structure limits and time per phase.");
  cmd->add_option("input", args->input, "Input mesh file")->required()->check(silkapp::ExistingFile());
  cmd->add_flag("--json", args->json, "Print JSON instead of text (default: text)");
  cmd->add_flag("--no-nonmanifold", args->no_nonmanifold, "Skip non-manifold processing (default: off)");
  cmd->callback([args] { ExitCode() = Run(*args); });
}

}  // namespace silktok
