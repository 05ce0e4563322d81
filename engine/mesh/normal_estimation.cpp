// SPDX-License-Identifier: MIT
// The estimation pipeline: checks, duplicates merged, the scale brought into range, kNN graph,
// one plane fit per neighbourhood, orientation.
#include "mesh/normal_estimation.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include "mesh/distinct_points.h"
#include "mesh/normal_orientation.h"
#include "mesh/plane_fit.h"

namespace silk {

namespace {

Status CheckInput(const std::vector<Point3>& points, const NormalEstimationParams& params) {
  if (params.neighbors < 3 || params.neighbors > 256)
    return InvalidArgument("normal estimation: neighbors " + std::to_string(params.neighbors) + " is not in 3..256");
  if (points.size() > static_cast<size_t>(std::max<int64_t>(params.max_points, 0)))
    return InvalidArgument("cannot estimate normals for " + std::to_string(points.size()) + " points: the limit is " +
                           std::to_string(params.max_points) +
                           " (give the cloud with normals x y z nx ny nz, or fewer points)");
  if (points.size() < 3)
    return InvalidArgument("cannot estimate normals from " + std::to_string(points.size()) +
                           " point(s): at least 3 are needed");
  for (size_t i = 0; i < points.size(); ++i)
    for (double x : points[i])
      if (!std::isfinite(x))
        return InvalidArgument("cannot estimate normals: point " + std::to_string(i) + " is not finite");
  return Status::Ok();
}

// The power of two that brings the cloud's extent near 1 when it lies outside [2^-32, 2^32],
// else 1 (ordinary clouds are not touched). A power of two scales exactly, so the normals are
// those of the cloud itself; without it a cloud at 1e-100 underflows its covariance (every
// plane fit gave an axis) and one at 1e200 overflows it.
double RangeScale(const std::vector<Point3>& points) {
  Point3 lo = points[0], hi = points[0];
  for (const Point3& p : points)
    for (int a = 0; a < 3; ++a) lo[a] = std::min(lo[a], p[a]), hi[a] = std::max(hi[a], p[a]);
  double extent = 0;
  for (int a = 0; a < 3; ++a) extent = std::max(extent, hi[a] / 2 - lo[a] / 2);  // halves: no overflow
  if (!(extent > 0) || (extent >= 0x1p-33 && extent <= 0x1p31)) return 1;
  int e = 0;
  std::frexp(extent, &e);
  return std::ldexp(1.0, -e);
}

StatusOr<std::vector<Point3>> EstimateDistinct(const std::vector<Point3>& points, const NormalEstimationParams& params,
                                               const CancelCheck& cancel) {
  SILK_ASSIGN_OR_RETURN(const KnnGraph graph, NearestNeighbors(points, params.neighbors, cancel));
  std::vector<Point3> normals(points.size());
  std::vector<int32_t> hood(graph.k + 1);
  for (size_t i = 0; i < points.size(); ++i) {
    if ((i + 1) % kCancelPollInterval == 0 && CancelRequested(cancel)) return CancelledStatus("normal estimation");
    hood[0] = static_cast<int32_t>(i);
    for (int32_t s = 0; s < graph.k; ++s) hood[s + 1] = graph.Of(i)[s];
    normals[i] = FitPlaneNormal(points, hood.data(), graph.k + 1);
  }
  SILK_RETURN_IF_ERROR(OrientNormals(points, graph, &normals, cancel).status());
  return normals;
}

}  // namespace

StatusOr<std::vector<Point3>> EstimateNormals(const std::vector<Point3>& points, const NormalEstimationParams& params,
                                              const CancelCheck& cancel) {
  SILK_RETURN_IF_ERROR(CheckInput(points, params));
  DistinctPoints distinct = MergeDuplicatePoints(points);
  if (distinct.merged() && distinct.points.size() < 3)
    return InvalidArgument("cannot estimate normals: the " + std::to_string(points.size()) + " points lie at " +
                           std::to_string(distinct.points.size()) + " distinct position(s), at least 3 are needed");
  const std::vector<Point3>& unique = distinct.merged() ? distinct.points : points;
  const double scale = RangeScale(unique);
  std::vector<Point3> scaled;
  if (scale != 1) {
    scaled = unique;
    for (Point3& p : scaled)
      for (double& x : p) x *= scale;
  }
  SILK_ASSIGN_OR_RETURN(std::vector<Point3> normals, EstimateDistinct(scale != 1 ? scaled : unique, params, cancel));
  if (!distinct.merged()) return normals;
  std::vector<Point3> all(points.size());
  for (size_t i = 0; i < points.size(); ++i) all[i] = normals[static_cast<size_t>(distinct.of[i])];
  return all;
}

}  // namespace silk
