// SPDX-License-Identifier: MIT
// Resolution of a GenerationRequest against the model's config, with its range checks.
#include "runtime/generation_request.h"

#include <cmath>
#include <string>
#include <utility>

#include "core/value_text.h"

namespace silk {

namespace {

// Unset, or a finite value in [0, hi] (hi infinite: any finite value >= 0).
Status CheckUnsetOr(const char* field, const std::optional<double>& value, double hi) {
  if (!value || (std::isfinite(*value) && *value >= 0 && *value <= hi)) return Status::Ok();
  const std::string range = std::isinf(hi) ? "a finite value >= 0" : "a value in [0, " + ValueText(hi) + "]";
  return InvalidArgument(std::string(field) + " " + ValueText(*value) +
                         " is neither SILK_MODEL_VALUE (-1: the model's) nor " + range);
}

Status CheckRequest(const GenerationRequest& r) {
  SILK_RETURN_IF_ERROR(CheckUnsetOr("temperature", r.temperature, HUGE_VAL));
  const std::optional<double> top_k = r.top_k ? std::optional<double>(*r.top_k) : std::nullopt;
  SILK_RETURN_IF_ERROR(CheckUnsetOr("top_k", top_k, INT32_MAX));
  SILK_RETURN_IF_ERROR(CheckUnsetOr("top_p", r.top_p, 1.0));
  SILK_RETURN_IF_ERROR(CheckUnsetOr("top_p_temperature", r.top_p_temperature, HUGE_VAL));
  if (r.candidates && (*r.candidates < 1 || *r.candidates > kMaxCandidates))
    return InvalidArgument("candidates " + std::to_string(*r.candidates) +
                           " is neither SILK_MODEL_VALUE (-1: the model's) nor in 1.." +
                           std::to_string(kMaxCandidates));
  if (r.face_tolerance && !(*r.face_tolerance >= kMinFaceTolerance && *r.face_tolerance <= kMaxFaceTolerance))
    return InvalidArgument("face_tolerance " + ValueText(*r.face_tolerance) +
                           " is neither SILK_MODEL_VALUE (-1: the model's) nor in " + ValueText(kMinFaceTolerance) +
                           ".." + ValueText(kMaxFaceTolerance) + " (cells)");
  if (r.n_points && *r.n_points < 1)
    return InvalidArgument("n_points " + std::to_string(*r.n_points) + (*r.n_points < 0 ? " is negative" : " is zero"));
  for (const auto& [field, value] :
       {std::pair<const char*, int32_t>{"max_tokens", r.max_tokens}, {"max_faces", r.max_faces}})
    if (value < 0) return InvalidArgument(std::string(field) + " " + std::to_string(value) + " is negative");
  return Status::Ok();
}

// The model's pre-processing with the request's n_points and kind (that kind's defaults).
PreprocessingParams ResolvePreprocessing(const GenerationRequest& r, const ModelConfig& config) {
  PreprocessingParams prep = config.preprocessing;
  if (r.n_points) prep.n_points = *r.n_points;
  if (r.preprocessing && *r.preprocessing != prep.kind)
    prep = *r.preprocessing == PreprocessingKind::kOfficial ? OfficialPreprocessing(prep.n_points)
                                                            : SilkPreprocessing(prep.normalize_bound, prep.n_points);
  return prep;
}

}  // namespace

const char* GenerationPlan::preprocessing_name() const {
  return raw_points ? "raw" : PreprocessingKindName(preprocessing.kind);
}

StatusOr<GenerationPlan> ResolveRequest(const GenerationRequest& r, const ModelConfig& config) {
  SILK_RETURN_IF_ERROR(CheckRequest(r));
  GenerationPlan plan;
  GenerateOptions& o = plan.options;
  o.sampling = config.sampling;
  o.sampling.seed = r.seed;
  o.sampling.temperature = r.temperature.value_or(o.sampling.temperature);
  o.sampling.top_k = r.top_k.value_or(o.sampling.top_k);
  o.sampling.top_p = r.top_p.value_or(o.sampling.top_p);
  o.sampling.top_p_temperature = r.top_p_temperature.value_or(o.sampling.top_p_temperature);
  o.max_tokens = r.max_tokens;
  o.max_faces = r.max_faces;
  o.holes = r.holes;
  o.unconstrained = r.unconstrained;
  o.record_trace = r.record_trace;
  o.surface_tolerance = r.surface_tolerance;
  o.candidates = r.candidates.value_or(config.candidates);
  o.orient_to_input = r.orient_to_input;
  o.face_guidance = r.face_guidance.value_or(config.face_guidance);
  o.face_tolerance = r.face_tolerance.value_or(config.face_tolerance);
  SILK_RETURN_IF_ERROR(CheckGenerateOptions(o));
  plan.preprocessing = ResolvePreprocessing(r, config);
  plan.raw_points = r.raw_points;
  return plan;
}

}  // namespace silk
