// JSON files silkgen writes besides the mesh: --stats (figures of one run) and --trace (the
// points and every generated id with its legal set, read by tests/models/reference_loop.py).
#pragma once
#include <string>
#include <vector>

#include "core/status.h"
#include "runtime/generate_pipeline.h"

namespace silkgen {

struct RunSettings {
  std::string input, output, model_dir, model_config;
  std::string preprocessing;  // "silk", "official" or "raw" (--raw-points)
  bool point_cloud = false;
  int32_t input_vertices = 0, input_faces = 0, points = 0;
  silk::GenerateOptions options;
};

std::string StatsJson(const RunSettings& settings, const silk::PipelineResult& result);
std::string TraceJson(const RunSettings& settings, const std::vector<float>& points, const silk::GenerateResult& gen);

}  // namespace silkgen
