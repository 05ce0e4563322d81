// SPDX-License-Identifier: MIT
// Chamfer distance: mean nearest-point distances both ways, and the mesh side sampled.
#include "mesh/chamfer_distance.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "mesh/surface_sampling.h"

namespace silk {

namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();
}  // namespace

namespace {
// The mean distance, summed in the same order whether or not `cancel` is polled (same value).
StatusOr<double> MeanDistance(const std::vector<Point3>& from, const NearestPointIndex& to, const CancelCheck& cancel) {
  if (from.empty()) return kInf;
  double sum = 0;
  for (size_t i = 0; i < from.size(); ++i) {
    if ((i + 1) % kChamferPollInterval == 0 && CancelRequested(cancel)) return CancelledStatus("scoring");
    sum += to.Distance(from[i]);
  }
  return sum / static_cast<double>(from.size());
}

// MeanDistance from `from` to a cancellable index of `to` (a million points take ~0.5 s to index).
StatusOr<double> MeanDistanceTo(const std::vector<Point3>& from, const std::vector<Point3>& to,
                                const CancelCheck& cancel) {
  const NearestPointIndex index(to, cancel);
  if (index.cancelled()) return CancelledStatus("scoring");
  return MeanDistance(from, index, cancel);
}
}  // namespace

StatusOr<ChamferDistance> PointSetChamfer(const std::vector<Point3>& a, const std::vector<Point3>& b,
                                          const CancelCheck& cancel) {
  ChamferDistance d;
  SILK_ASSIGN_OR_RETURN(d.a_to_b, MeanDistanceTo(a, b, cancel));
  if (CancelRequested(cancel)) return CancelledStatus("scoring");
  SILK_ASSIGN_OR_RETURN(d.b_to_a, MeanDistanceTo(b, a, cancel));
  return d;
}

ChamferDistance PointSetChamfer(const std::vector<Point3>& a, const std::vector<Point3>& b) {
  return PointSetChamfer(a, b, CancelCheck{}).value();
}

StatusOr<ChamferDistance> MeshToPointsChamfer(const IoMesh& mesh, const std::vector<Point3>& points, int32_t samples,
                                              uint64_t seed, const CancelCheck& cancel) {
  auto s = SampleSurface(mesh, samples, seed);
  if (!s.ok() || s->empty()) return ChamferDistance{kInf, kInf};
  std::vector<Point3> a;
  a.reserve(s->size());
  for (const OrientedPoint& p : *s) a.push_back(p.position);
  return PointSetChamfer(a, points, cancel);
}

ChamferDistance MeshToPointsChamfer(const IoMesh& mesh, const std::vector<Point3>& points, int32_t samples,
                                    uint64_t seed) {
  return MeshToPointsChamfer(mesh, points, samples, seed, CancelCheck{}).value();
}

}  // namespace silk
