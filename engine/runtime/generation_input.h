// SPDX-License-Identifier: MIT
// The input of a generation and its way to the encoder: the caller's mesh or point cloud
// (GenerationInput), its checks, and the model's pre-processing (or raw points as given) into
// the encoder's points with the transform back to the input frame.
#pragma once
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "core/cancel_check.h"
#include "core/status.h"
#include "io/io_mesh.h"
#include "mesh/point_preprocessing.h"
#include "runtime/model/model_config.h"

namespace silk {

struct GenerationInput {
  IoMesh mesh;                                 // triangles empty for a point cloud
  std::vector<std::array<double, 3>> normals;  // point cloud: one per position
  bool point_cloud = false;
  std::string name;  // for messages: the file it came from; "" = "input"
};

// Checks a caller-built input (sizes, finite values, index ranges); polls `cancel` every
// kCancelPollInterval points (kCancelled).
Status ValidateGenerationInput(const GenerationInput& input, const CancelCheck& cancel = {});

// The model's pre-processing (model.json "preprocessing", mesh/point_preprocessing.h) on a
// validated input: normalised points and the transform back to the input frame.
StatusOr<PreparedPoints> PrepareModelPoints(const GenerationInput& input, const PreprocessingParams& params,
                                            uint64_t seed, const CancelCheck& cancel = {});
// The model's pre-processing with n_points (0: the model's own).
PreprocessingParams ModelPreprocessing(const ModelConfig& config, int32_t n_points = 0);

// A point cloud used exactly as given (silkgen --raw-points): no normalisation, resampling or
// rounding, identity transform (the output stays in the model's frame). Its point count must
// be `n_points`; every value must be finite.
StatusOr<PreparedPoints> RawModelPoints(const GenerationInput& input, int32_t n_points);

}  // namespace silk
