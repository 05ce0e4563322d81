// SPDX-License-Identifier: MIT
// Normals for a point cloud that has none (a scan exported without them): a plane fitted to
// each point's k nearest neighbours (PCA, mesh/plane_fit) gives the normal line, and Hoppe's
// minimum-spanning-tree propagation (mesh/normal_orientation) gives consistent, outward signs.
// Accuracy per k is measured in docs/normals.md (bench/normal_estimation_bench).
#pragma once
#include <cstdint>
#include <vector>

#include "core/status.h"
#include "mesh/nearest_points.h"

namespace silk {

// Neighbours per point; chosen by measurement on the dev corpus (docs/normals.md).
inline constexpr int32_t kDefaultNormalNeighbors = 16;

struct NormalEstimationParams {
  int32_t neighbors = kDefaultNormalNeighbors;  // k, 3..256 (fewer when the cloud is smaller)
};

// Unit normals, one per point, deterministic (one thread; ties broken by index). Needs at least
// 3 finite points; otherwise an InvalidArgument naming the problem.
StatusOr<std::vector<Point3>> EstimateNormals(const std::vector<Point3>& points,
                                              const NormalEstimationParams& params = {});

}  // namespace silk
