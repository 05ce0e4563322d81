// SPDX-License-Identifier: MIT
// C API: the caller's silk_generate_params and silk_generate_input as the runtime's request and
// input (and its progress reports back), for every call that generates (the generator's start
// and run, the batch's add).
#if defined(SILK_HAVE_RUNTIME)
#include <string>

#include "capi/capi_generator.h"

namespace silk::capi {

namespace {

constexpr int32_t kAllReportFlags = SILK_GENERATE_RECORD_TRACE;

// The C-only checks of the params: flags 0/1, enums in range, reserved slots 0. Value ranges
// are the runtime's (ResolveRequest).
silk::Status CheckParams(const silk_generate_params& p) {
  using silk::capi::CheckEnum;
  using silk::capi::CheckFlag;
  SILK_RETURN_IF_ERROR(CheckEnum("holes", p.holes, SILK_HOLES_OFF, SILK_HOLES_REPAIR, "silk_hole_policy"));
  SILK_RETURN_IF_ERROR(CheckFlag("raw_points", p.raw_points));
  SILK_RETURN_IF_ERROR(CheckEnum("orient", p.orient, SILK_ORIENT_TOKENS, SILK_ORIENT_INPUT, "silk_orientation"));
  if (p.preprocessing != SILK_MODEL_VALUE)
    SILK_RETURN_IF_ERROR(CheckEnum("preprocessing", p.preprocessing, SILK_PREPROCESS_SILK, SILK_PREPROCESS_OFFICIAL,
                                   "silk_preprocess_kind (or SILK_MODEL_VALUE, -1)"));
  if (p.face_guidance != SILK_MODEL_VALUE)
    SILK_RETURN_IF_ERROR(CheckEnum("face_guidance", p.face_guidance, SILK_FACE_GUIDANCE_OFF, SILK_FACE_GUIDANCE_SOFT,
                                   "silk_face_guidance (or SILK_MODEL_VALUE, -1)"));
  for (int i = 0; i < 2; ++i)  // 1.0-1.3: unconstrained, debug_flags (measurement switches, no longer public)
    if (p.reserved[i] != 0)
      return silk::InvalidArgument("reserved[" + std::to_string(i) + "] is " + std::to_string(p.reserved[i]) +
                                   ", not 0 (C API 1.0-1.3's " + (i == 0 ? "unconstrained" : "debug_flags") +
                                   ", a measurement switch that is no longer part of the API)");
  if (p.report_flags & ~kAllReportFlags)
    return silk::InvalidArgument("report_flags " + std::to_string(p.report_flags) + " has unknown bits");
  return silk::Status::Ok();
}

}  // namespace

// The C params as the runtime's request: SILK_MODEL_VALUE (and point_count 0) become "unset", the
// model's value; anything else is passed on as given, for the runtime to check. `unconstrained`:
// the generator's measurement mode (capi/capi_measurement.h), never a params field.
silk::StatusOr<silk::GenerationRequest> ToRequest(const silk_generate_params& p, bool unconstrained) {
  SILK_RETURN_IF_ERROR(CheckParams(p));
  silk::GenerationRequest r;
  r.seed = p.seed;
  if (p.temperature != SILK_MODEL_VALUE) r.temperature = p.temperature;
  if (p.top_k != SILK_MODEL_VALUE) r.top_k = p.top_k;
  if (p.top_p != SILK_MODEL_VALUE) r.top_p = p.top_p;
  if (p.top_p_temperature != SILK_MODEL_VALUE) r.top_p_temperature = p.top_p_temperature;
  if (p.candidates != SILK_MODEL_VALUE) r.candidates = p.candidates;
  if (p.rows != SILK_MODEL_VALUE) r.rows = p.rows;
  if (p.preprocessing != SILK_MODEL_VALUE)
    r.preprocessing = p.preprocessing == SILK_PREPROCESS_OFFICIAL ? silk::PreprocessingKind::kOfficial
                                                                  : silk::PreprocessingKind::kSilk;
  if (p.point_count != 0) r.n_points = p.point_count;
  r.raw_points = p.raw_points != 0;
  r.max_tokens = p.max_tokens;
  r.max_faces = p.max_faces;
  r.holes = p.holes == SILK_HOLES_REPAIR   ? silk::HolePolicy::kRepair
            : p.holes == SILK_HOLES_REPORT ? silk::HolePolicy::kReport
                                           : silk::HolePolicy::kOff;
  r.unconstrained = unconstrained;
  r.record_trace = (p.report_flags & SILK_GENERATE_RECORD_TRACE) != 0;
  r.surface_tolerance = p.surface_tolerance;
  r.orient_to_input = p.orient == SILK_ORIENT_INPUT;
  if (p.face_guidance != SILK_MODEL_VALUE) r.face_guidance = static_cast<silk::FaceGuidance>(p.face_guidance);
  if (p.face_tolerance != SILK_MODEL_VALUE) r.face_tolerance = p.face_tolerance;
  return r;
}

// The caller's input as the runtime's GenerationInput (mesh, point cloud, or raw points); polls
// `cancel` every kCancelPollInterval points (a million take ~10 ms to convert). The session checks it.
silk::StatusOr<silk::GenerationInput> ToInput(const silk_generate_input& in, const silk::CancelCheck& cancel) {
  if ((in.mesh != nullptr) == (in.points != nullptr)) return silk::InvalidArgument("give exactly one of mesh, points");
  silk::GenerationInput out;
  if (in.mesh) {
    out.mesh = in.mesh->mesh;
    out.normals = in.mesh->normals;
    out.point_cloud = out.mesh.triangles.empty() && !out.normals.empty();
    out.name = in.mesh->source;
    return out;
  }
  if (in.point_rows == 0) return silk::InvalidArgument("no points (point_rows is 0)");
  if (in.point_rows > (size_t{1} << 26)) return silk::InvalidArgument("more than 2^26 points");
  out.point_cloud = true;
  out.mesh.positions.resize(in.point_rows);
  out.normals.resize(in.point_rows);
  for (size_t i = 0; i < in.point_rows; ++i) {
    if (i % silk::kCancelPollInterval == 0 && silk::CancelRequested(cancel))
      return silk::CancelledStatus("input conversion");
    for (int a = 0; a < 3; ++a) {
      out.mesh.positions[i][a] = in.points[6 * i + a];
      out.normals[i][a] = in.points[6 * i + 3 + a];
    }
  }
  return out;
}

silk_generate_progress ToCProgress(const GenerateProgress& x) {
  return silk_generate_progress{sizeof(silk_generate_progress),
                                x.tokens,
                                x.max_tokens,
                                x.components,
                                x.faces,
                                x.seconds,
                                x.candidate,
                                x.candidates};
}

}  // namespace silk::capi
#endif
