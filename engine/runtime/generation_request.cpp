// SPDX-License-Identifier: MIT
// Resolution of a GenerationRequest against the model's config, with its range checks.
#include "runtime/generation_request.h"

#include <string>
#include <utility>

#include "runtime/sampling/generation_ranges.h"

namespace silk {

namespace {

// A value the caller gave, by the settings' range table; the message adds that -1 takes the
// model's value.
Status CheckGiven(const SettingRange& range, double value) {
  const Status s = CheckSetting(range, value);
  return s.ok() ? s : InvalidArgument(s.message() + "; SILK_MODEL_VALUE (-1) takes the model's");
}

// Each value the request sets, by the settings' range table (unset values are the model's, which
// model.json's parse has checked by the same table).
Status CheckRequest(const GenerationRequest& r) {
  auto given = [](const auto& v) { return v ? std::optional<double>(*v) : std::nullopt; };
  for (const auto& [range, value] : {std::pair{ranges::kTemperature, r.temperature},
                                     {ranges::kTopK, given(r.top_k)},
                                     {ranges::kTopP, r.top_p},
                                     {ranges::kTopPTemperature, r.top_p_temperature},
                                     {ranges::kCandidates, given(r.candidates)},
                                     {ranges::kRows, given(r.rows)},
                                     {ranges::kFaceTolerance, r.face_tolerance}})
    if (value) SILK_RETURN_IF_ERROR(CheckGiven(range, *value));
  if (r.n_points) SILK_RETURN_IF_ERROR(CheckSetting(ranges::kPointCount, *r.n_points));
  for (const auto& [range, value] : {std::pair{ranges::kMaxTokens, r.max_tokens},
                                     {ranges::kMaxFaces, r.max_faces},
                                     {ranges::kSurfaceTolerance, r.surface_tolerance}})
    SILK_RETURN_IF_ERROR(CheckSetting(range, value));
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
  o.rows = ResolveRows(r.rows, config);
  o.orient_to_input = r.orient_to_input;
  o.face_guidance = r.face_guidance.value_or(config.face_guidance);
  o.face_tolerance = r.face_tolerance.value_or(config.face_tolerance);
  SILK_RETURN_IF_ERROR(CheckGenerateOptions(o));
  plan.preprocessing = ResolvePreprocessing(r, config);
  plan.raw_points = r.raw_points;
  return plan;
}

int32_t ResolveRows(std::optional<int32_t> asked, const ModelConfig& config) {
  return asked.value_or(config.rows.value_or(kDefaultRows));
}

}  // namespace silk
