// SPDX-License-Identifier: MIT
// The pre-processing steps in order (see the header), with the checks of its inputs.
#include "mesh/point_preprocessing.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "core/splitmix64.h"
#include "mesh/close_vertex_merge.h"
#include "mesh/float16_rounding.h"
#include "mesh/surface_sampling.h"

namespace silk {

namespace {

constexpr int32_t kMaxSurfaceSamples = 10000000;

// "preprocessing.FIELD VALUE WHAT": the field and the value given.
Status BadField(const char* field, double value, const std::string& what) {
  std::ostringstream v;
  v << value;
  return InvalidArgument(std::string("preprocessing.") + field + " " + v.str() + " " + what);
}

std::vector<OrientedPoint> CloudPoints(const IoMesh& normalized, const std::vector<std::array<double, 3>>& normals) {
  std::vector<OrientedPoint> pts;
  pts.reserve(normalized.positions.size());
  for (size_t i = 0; i < normalized.positions.size(); ++i) {
    const auto& n = normals[i];
    const double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    pts.push_back({normalized.positions[i], {n[0] / len, n[1] / len, n[2] / len}});
  }
  return pts;
}

std::vector<std::array<double, 3>> RowColumns(const std::vector<float>& rows, size_t first) {
  std::vector<std::array<double, 3>> out;
  out.reserve(rows.size() / 6);
  for (size_t i = 0; i + 6 <= rows.size(); i += 6)
    out.push_back({rows[i + first], rows[i + first + 1], rows[i + first + 2]});
  return out;
}

}  // namespace

std::vector<std::array<double, 3>> PointRowPositions(const std::vector<float>& rows) { return RowColumns(rows, 0); }
std::vector<std::array<double, 3>> PointRowNormals(const std::vector<float>& rows) { return RowColumns(rows, 3); }

PreprocessingParams SilkPreprocessing(double normalize_bound, int32_t n_points) {
  PreprocessingParams p;
  p.normalize_bound = normalize_bound;
  p.n_points = n_points;
  return p;
}

PreprocessingParams OfficialPreprocessing(int32_t n_points) {
  PreprocessingParams p;
  p.kind = PreprocessingKind::kOfficial;
  p.normalize_bound = 0.95;
  p.merge_distance_fraction = 0.01;
  p.surface_samples = 50000;
  p.round_float16 = true;
  p.n_points = n_points;
  return p;
}

const char* PreprocessingKindName(PreprocessingKind kind) {
  return kind == PreprocessingKind::kOfficial ? "official" : "silk";
}

Status ValidatePreprocessing(const PreprocessingParams& p) {
  if (p.kind != PreprocessingKind::kSilk && p.kind != PreprocessingKind::kOfficial)
    return BadField("kind", static_cast<int>(p.kind), "is neither \"silk\" nor \"official\"");
  if (!(p.normalize_bound > 0 && p.normalize_bound <= 1))
    return BadField("normalize_bound", p.normalize_bound, "must be in (0, 1]");
  if (!(p.merge_distance_fraction >= 0 && p.merge_distance_fraction <= 0.5))
    return BadField("merge_distance_fraction", p.merge_distance_fraction, "must be in [0, 0.5]");
  if (p.surface_samples < 0 || p.surface_samples > kMaxSurfaceSamples)
    return BadField("surface_samples", p.surface_samples, "must be in [0, " + std::to_string(kMaxSurfaceSamples) + "]");
  if (p.n_points <= 0 || p.n_points > kMaxPreprocessingPoints)
    return BadField("n_points", p.n_points, "must be in [1, " + std::to_string(kMaxPreprocessingPoints) + "]");
  return Status::Ok();
}

StatusOr<PreparedPoints> PreparePoints(const IoMesh& mesh, const std::vector<std::array<double, 3>>* normals,
                                       const PreprocessingParams& p, uint64_t seed, const CancelCheck& cancel) {
  SILK_RETURN_IF_ERROR(ValidatePreprocessing(p));
  if (normals && normals->size() != mesh.positions.size())
    return InvalidArgument("point cloud: " + std::to_string(normals->size()) + " normals for " +
                           std::to_string(mesh.positions.size()) + " points");
  const int64_t nv = static_cast<int64_t>(mesh.positions.size());
  for (size_t f = 0; f < mesh.triangles.size(); ++f)
    for (int32_t v : mesh.triangles[f])
      if (v < 0 || v >= nv) return InvalidArgument("triangle " + std::to_string(f) + " has an index out of range");
  const bool official = p.kind == PreprocessingKind::kOfficial;
  IoMesh cleaned;
  const IoMesh* source = &mesh;
  if (!normals && (official || p.merge_distance_fraction > 0)) {
    cleaned = MergeCloseVertices(mesh, p.merge_distance_fraction * ReferencedBoundingBoxDiagonal(mesh));
    if (cleaned.triangles.empty()) return InvalidArgument("the mesh has no face with positive area");
    source = &cleaned;
  }
  if (CancelRequested(cancel)) return CancelledStatus("pre-processing");
  PreparedPoints out;
  SILK_ASSIGN_OR_RETURN(out.transform, ComputeNormalization(*source, p.normalize_bound));
  const IoMesh normalized = ApplyNormalization(*source, out.transform);
  std::vector<OrientedPoint> pts;
  if (normals) {
    pts = CloudPoints(normalized, *normals);
  } else {
    SILK_ASSIGN_OR_RETURN(pts, SampleSurface(normalized, std::max(p.surface_samples, p.n_points), seed, cancel));
  }
  if (CancelRequested(cancel)) return CancelledStatus("pre-processing");
  if (p.round_float16)
    for (OrientedPoint& q : pts)
      for (int a = 0; a < 3; ++a)
        q.position[a] = RoundToFloat16(q.position[a]), q.normal[a] = RoundToFloat16(q.normal[a]);
  // Silk's kind keeps its historical seeds (sampling n_points directly, or the cloud subset
  // with `seed`); a separate stream draws the subset after oversampling.
  const bool oversampled = !normals && pts.size() > static_cast<size_t>(p.n_points);
  pts = SubsamplePoints(pts, p.n_points, oversampled || official ? SplitMix64(seed ^ 0x5EEDD1A5u).Next() : seed);
  out.rows.reserve(pts.size() * 6);
  for (const OrientedPoint& q : pts) {
    for (double v : q.position) out.rows.push_back(static_cast<float>(v));
    for (double v : q.normal) out.rows.push_back(static_cast<float>(v));
  }
  return out;
}

}  // namespace silk
