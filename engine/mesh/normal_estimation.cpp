// SPDX-License-Identifier: MIT
// The estimation pipeline: checks, kNN graph, one plane fit per neighbourhood, orientation.
#include "mesh/normal_estimation.h"

#include <cmath>
#include <string>

#include "mesh/normal_orientation.h"
#include "mesh/plane_fit.h"

namespace silk {

StatusOr<std::vector<Point3>> EstimateNormals(const std::vector<Point3>& points, const NormalEstimationParams& params) {
  if (params.neighbors < 3 || params.neighbors > 256)
    return InvalidArgument("normal estimation: neighbors " + std::to_string(params.neighbors) + " is not in 3..256");
  if (points.size() < 3)
    return InvalidArgument("cannot estimate normals from " + std::to_string(points.size()) +
                           " point(s): at least 3 are needed");
  for (size_t i = 0; i < points.size(); ++i)
    for (double x : points[i])
      if (!std::isfinite(x)) return InvalidArgument("cannot estimate normals: point " + std::to_string(i) + " is not finite");
  const KnnGraph graph = NearestNeighbors(points, params.neighbors);
  std::vector<Point3> normals(points.size());
  std::vector<int32_t> hood(graph.k + 1);
  for (size_t i = 0; i < points.size(); ++i) {
    hood[0] = static_cast<int32_t>(i);
    for (int32_t s = 0; s < graph.k; ++s) hood[s + 1] = graph.Of(i)[s];
    normals[i] = FitPlaneNormal(points, hood.data(), graph.k + 1);
  }
  OrientNormals(points, graph, &normals);
  return normals;
}

}  // namespace silk
