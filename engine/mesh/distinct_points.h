// SPDX-License-Identifier: MIT
// Exact duplicates in a point cloud merged before any neighbourhood search: n copies of one point
// are all at distance 0 from each other, which defeats a k-d tree's pruning (every query visits
// every copy: 100,000 identical points took minutes) and gives no plane to fit.
#pragma once
#include <cstdint>
#include <vector>

#include "mesh/nearest_points.h"

namespace silk {

struct DistinctPoints {
  // Empty when the cloud has no duplicate (the common case: nothing is copied). Otherwise
  // points: the first occurrence of each position, in input order; of[i]: the index in points
  // of input point i's position.
  std::vector<Point3> points;
  std::vector<int32_t> of;
  bool merged() const { return !of.empty(); }
};

// O(n log n): a sort of the indices by (x, y, z, index). Coordinates compare as doubles (0.0 and
// -0.0 are one position). At most INT32_MAX points.
DistinctPoints MergeDuplicatePoints(const std::vector<Point3>& points);

}  // namespace silk
