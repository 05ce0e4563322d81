// SPDX-License-Identifier: MIT
// What a caller asks of one generation (silk_generate_params in the runtime's terms), with "the
// model's value" left unset, and its one resolution against the model (model.json "sampling",
// "preprocessing"): every unset value filled in, every value range-checked by the one range table
// (runtime/sampling/generation_ranges.h) with a message that names the field, the value and the range.
#pragma once
#include <cstdint>
#include <optional>

#include "core/status.h"
#include "mesh/point_preprocessing.h"
#include "runtime/generator.h"
#include "runtime/model/model_config.h"

namespace silk {

struct GenerationRequest {
  uint64_t seed = 0;  // sampling (candidate 0; CandidateSeed for the others) and pre-processing
  // Unset: the model's (model.json "sampling"; DefaultSamplingParams for a v2 model).
  std::optional<double> temperature, top_p, top_p_temperature;
  std::optional<int32_t> top_k;
  std::optional<int32_t> candidates;  // best of N (ranges::kCandidates); unset: the model's N
  std::optional<int32_t> rows;        // best of N's rows (ranges::kRows); unset: the model's, else kDefaultRows
  std::optional<PreprocessingKind> preprocessing;  // unset: model.json "preprocessing"
  std::optional<int32_t> n_points;                 // encoder points; unset: the model's pre-processing's
  bool raw_points = false;                         // the input's points are the encoder input as given (RawModelPoints)
  int32_t max_tokens = 0, max_faces = 0;           // GenerateOptions' caps
  HolePolicy holes = HolePolicy::kOff;
  bool unconstrained = false;  // GenerateOptions::unconstrained (no public params field)
  bool record_trace = false;
  int32_t surface_tolerance = 0;
  bool orient_to_input = false;
  // Unset: the model's (model.json sampling.face_guidance / face_tolerance, else libsilk's).
  std::optional<FaceGuidance> face_guidance;
  std::optional<double> face_tolerance;  // cells (ranges::kFaceTolerance)
};

// A request resolved: what the session runs.
struct GenerationPlan {
  GenerateOptions options;            // sampling resolved, seed = the request's, candidates = N, rows
  PreprocessingParams preprocessing;  // the model's, with the request's kind and n_points
  bool raw_points = false;
  // "raw", or the pre-processing kind's name ("silk", "official").
  const char* preprocessing_name() const;
};

// Fills the request's unset values from `config` and checks every value (NaN, negative, out of
// range: InvalidArgument naming the field and value, then CheckGenerateOptions).
StatusOr<GenerationPlan> ResolveRequest(const GenerationRequest& request, const ModelConfig& config);

// Best of N's rows when `asked` is unset: the model's (model.json sampling.rows), else kDefaultRows.
int32_t ResolveRows(std::optional<int32_t> asked, const ModelConfig& config);

}  // namespace silk
