// SPDX-License-Identifier: MIT
// Checks of a generation's input and its preparation into the encoder's points.
#include "runtime/generation_input.h"

#include <cmath>

namespace silk {

Status ValidateGenerationInput(const GenerationInput& in, const CancelCheck& cancel) {
  if (in.mesh.positions.empty()) return InvalidArgument("input has no vertices");
  if (in.point_cloud) {
    if (in.normals.size() != in.mesh.positions.size())
      return InvalidArgument("point cloud: " + std::to_string(in.normals.size()) + " normals for " +
                             std::to_string(in.mesh.positions.size()) + " points");
    for (size_t i = 0; i < in.normals.size(); ++i) {
      if (i % kCancelPollInterval == 0 && CancelRequested(cancel)) return CancelledStatus("the input check");
      const auto& n = in.normals[i];
      const double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
      if (!std::isfinite(len) || len == 0)
        return InvalidArgument("point " + std::to_string(i) + " has a zero or non-finite normal");
    }
  } else if (in.mesh.triangles.empty()) {
    return InvalidArgument("input mesh has no faces");
  }
  return Status::Ok();
}

StatusOr<PreparedPoints> PrepareModelPoints(const GenerationInput& in, const PreprocessingParams& params, uint64_t seed,
                                            const CancelCheck& cancel) {
  SILK_RETURN_IF_ERROR(ValidateGenerationInput(in));
  return PreparePoints(in.mesh, in.point_cloud ? &in.normals : nullptr, params, seed, cancel);
}

PreprocessingParams ModelPreprocessing(const ModelConfig& config, int32_t n_points) {
  PreprocessingParams p = config.preprocessing;
  if (n_points > 0) p.n_points = n_points;
  return p;
}

StatusOr<PreparedPoints> RawModelPoints(const GenerationInput& in, int32_t n_points) {
  if (!in.point_cloud) return InvalidArgument("raw points need a point-cloud PLY (x y z nx ny nz, no faces)");
  if (in.mesh.positions.size() != static_cast<size_t>(n_points))
    return InvalidArgument("raw points: the file has " + std::to_string(in.mesh.positions.size()) +
                           " points, the model takes " + std::to_string(n_points));
  PreparedPoints out;
  out.rows.reserve(in.mesh.positions.size() * 6);
  for (size_t i = 0; i < in.mesh.positions.size(); ++i)
    for (const auto* v : {&in.mesh.positions[i], &in.normals[i]})
      for (double x : *v) {
        if (!std::isfinite(x)) return InvalidArgument("raw points: point " + std::to_string(i) + " is not finite");
        out.rows.push_back(static_cast<float>(x));
      }
  return out;
}

}  // namespace silk
