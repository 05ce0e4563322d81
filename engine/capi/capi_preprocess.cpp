// SPDX-License-Identifier: MIT
// C API: the encoder's point pre-processing (engine/mesh/point_preprocessing), available in
// every libsilk (no onnxruntime needed), so training code samples exactly like generation.
#include <cmath>
#include <cstring>
#include <string>

#include "capi/capi_internal.h"

using silk::capi::Guard;
using silk::capi::Ok;
using silk::capi::SetError;

namespace silk::capi {

silk_preprocess_params ToCPreprocess(const PreprocessingParams& p) {
  silk_preprocess_params c;
  std::memset(&c, 0, sizeof(c));
  c.struct_size = sizeof(c);
  c.kind = p.kind == PreprocessingKind::kOfficial ? SILK_PREPROCESS_OFFICIAL : SILK_PREPROCESS_SILK;
  c.normalize_bound = p.normalize_bound;
  c.merge_distance_fraction = p.merge_distance_fraction;
  c.surface_samples = p.surface_samples;
  c.round_float16 = p.round_float16 ? 1 : 0;
  c.point_count = p.n_points;
  return c;
}

PreprocessingParams FromCPreprocess(const silk_preprocess_params& c) {
  PreprocessingParams p;
  p.kind = c.kind == SILK_PREPROCESS_OFFICIAL ? PreprocessingKind::kOfficial : PreprocessingKind::kSilk;
  p.normalize_bound = c.normalize_bound;
  p.merge_distance_fraction = c.merge_distance_fraction;
  p.surface_samples = c.surface_samples;
  p.round_float16 = c.round_float16 != 0;
  p.n_points = c.point_count;
  return p;
}

}  // namespace silk::capi

extern "C" {

silk_preprocess_params silk_preprocess_default_params(int32_t kind) {
  return silk::capi::ToCPreprocess(kind == SILK_PREPROCESS_OFFICIAL ? silk::OfficialPreprocessing(4096)
                                                                    : silk::SilkPreprocessing(0.95, 4096));
}

silk_status silk_points_prepare(const silk_mesh* mesh, const double* cloud, size_t n_cloud,
                                const silk_preprocess_params* params, uint64_t seed, float* out, size_t capacity,
                                size_t* out_count, double* transform) {
  return Guard([&] {
    if (out_count) *out_count = 0;
    SILK_CAPI_REQUIRE((mesh != nullptr) != (cloud != nullptr), "silk_points_prepare: give either a mesh or a cloud");
    SILK_CAPI_REQUIRE(!cloud || n_cloud > 0, "silk_points_prepare: the cloud has no points");
    SILK_CAPI_TRY(silk::capi::CheckParamsSize("silk_points_prepare", "silk_preprocess_params", params,
                                              "silk_preprocess_default_params(kind)"));
    const silk_preprocess_params cp =
        silk::capi::ReadParams(params, silk_preprocess_default_params(SILK_PREPROCESS_SILK));
    for (const silk::Status& s : {silk::capi::CheckEnum("kind", cp.kind, SILK_PREPROCESS_SILK, SILK_PREPROCESS_OFFICIAL,
                                                        "silk_preprocess_kind"),
                                  silk::capi::CheckFlag("round_float16", cp.round_float16)})
      if (!s.ok()) return SetError(s.WithContext("silk_points_prepare: "));
    const silk::PreprocessingParams p = silk::capi::FromCPreprocess(cp);
    if (silk::Status s = silk::ValidatePreprocessing(p); !s.ok())
      return SetError(s.WithContext("silk_points_prepare: "));
    const size_t rows = cloud && n_cloud < static_cast<size_t>(p.n_points) ? n_cloud : static_cast<size_t>(p.n_points);
    if (silk_status c; !silk::capi::BeginCopy("silk_points_prepare", out, capacity, rows * 6, out_count, &c)) return c;
    silk::IoMesh cloud_mesh;
    std::vector<std::array<double, 3>> normals;
    if (cloud) {
      cloud_mesh.positions.resize(n_cloud);
      normals.resize(n_cloud);
      for (size_t i = 0; i < n_cloud; ++i)
        for (int a = 0; a < 3; ++a) cloud_mesh.positions[i][a] = cloud[6 * i + a], normals[i][a] = cloud[6 * i + 3 + a];
      for (size_t i = 0; i < n_cloud; ++i) {
        const auto& n = normals[i];
        const double len2 = n[0] * n[0] + n[1] * n[1] + n[2] * n[2];
        SILK_CAPI_REQUIRE(len2 > 0 && std::isfinite(len2),
                          "silk_points_prepare: point " + std::to_string(i) + " has a zero or non-finite normal");
      }
    } else {
      SILK_CAPI_REQUIRE(!mesh->mesh.triangles.empty(), "silk_points_prepare: the mesh has no faces");
    }
    auto r = silk::PreparePoints(cloud ? cloud_mesh : mesh->mesh, cloud ? &normals : nullptr, p, seed);
    if (!r.ok()) return SetError(r.status().WithContext("silk_points_prepare: "));
    if (r->rows.size() != rows * 6) return SetError(SILK_ERR_INTERNAL, "silk_points_prepare: unexpected row count");
    std::memcpy(out, r->rows.data(), r->rows.size() * sizeof(float));
    if (transform) {
      for (int a = 0; a < 3; ++a) transform[a] = r->transform.center[a];
      transform[3] = r->transform.scale;
    }
    return Ok();
  });
}

}  // extern "C"
