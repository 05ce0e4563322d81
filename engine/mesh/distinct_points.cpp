// SPDX-License-Identifier: MIT
// Duplicate merging by one index sort: equal positions become adjacent, the lowest index of each
// run is its representative, representatives keep their input order.
#include "mesh/distinct_points.h"

#include <algorithm>
#include <numeric>

namespace silk {

DistinctPoints MergeDuplicatePoints(const std::vector<Point3>& points) {
  DistinctPoints out;
  const int32_t n = static_cast<int32_t>(points.size());
  std::vector<int32_t> order(points.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(),
            [&](int32_t a, int32_t b) { return points[a] < points[b] || (points[a] == points[b] && a < b); });
  // rep[i]: the lowest index at input point i's position (the run's first, sorted by index).
  std::vector<int32_t>& rep = out.of;
  rep.resize(points.size());
  bool any = false;
  for (int32_t r = 0; r < n; ++r) {
    const bool same = r > 0 && points[order[r]] == points[order[r - 1]];
    rep[order[r]] = same ? rep[order[r - 1]] : order[r];
    any = any || same;
  }
  std::vector<int32_t>().swap(order);
  if (!any) {
    std::vector<int32_t>().swap(rep);
    return out;
  }
  // Representatives in input order get consecutive ids; a duplicate's rep precedes it.
  for (int32_t i = 0; i < n; ++i) {
    if (rep[i] == i) {
      rep[i] = static_cast<int32_t>(out.points.size());
      out.points.push_back(points[i]);
    } else {
      rep[i] = rep[rep[i]];
    }
  }
  out.points.shrink_to_fit();
  return out;
}

}  // namespace silk
