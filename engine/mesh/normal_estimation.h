// SPDX-License-Identifier: MIT
// Normals for a point cloud that has none (a scan exported without them): a plane fitted to
// each point's k nearest neighbours (PCA, mesh/plane_fit) gives the normal line, and Hoppe's
// minimum-spanning-tree propagation (mesh/normal_orientation) gives consistent, outward signs.
// Accuracy per k is measured in docs/normals.md (bench/normal_estimation_bench).
#pragma once
#include <cstdint>
#include <vector>

#include "core/cancel_check.h"
#include "core/status.h"
#include "mesh/nearest_points.h"

namespace silk {

// Neighbours per point; chosen by measurement on the dev corpus (docs/normals.md).
inline constexpr int32_t kDefaultNormalNeighbors = 16;
// The most points a cloud without normals may have: at the measured ~141 bytes per point above
// the input and ~7 us per point at this size (docs/normals.md, bench/normal_estimation_memory),
// 1 M points take about 165 MB with the input and under 10 s on one core.
inline constexpr int64_t kMaxNormalEstimationPoints = 1'000'000;

struct NormalEstimationParams {
  int32_t neighbors = kDefaultNormalNeighbors;  // k, 3..256 (fewer when the cloud is smaller)
  int64_t max_points = kMaxNormalEstimationPoints;
};

// Unit normals, one per point, deterministic (one thread; ties broken by index). Exact duplicate
// positions are merged first (each copy gets its position's normal); a cloud whose extent lies
// outside [2^-32, 2^32] is estimated at an exact power-of-two scale. InvalidArgument naming the
// problem for more than max_points points, a non-finite one, or fewer than 3 distinct positions;
// kCancelled when `cancel` (polled every kCancelPollInterval points) asks to stop.
StatusOr<std::vector<Point3>> EstimateNormals(const std::vector<Point3>& points,
                                              const NormalEstimationParams& params = {},
                                              const CancelCheck& cancel = {});

}  // namespace silk
