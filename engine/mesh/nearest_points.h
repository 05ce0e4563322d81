// SPDX-License-Identifier: MIT
// Nearest points of a fixed point set (one k-d tree of our own): the Chamfer score's nearest
// point, the input normal a generated vertex borrows, and the neighbourhoods normal estimation
// fits its planes to and propagates orientation along.
#pragma once
#include <array>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "core/cancel_check.h"
#include "core/status.h"

namespace silk {

using Point3 = std::array<double, 3>;

// A k-d tree over a fixed point set (median splits on the widest axis, leaves of <= 8 points).
// Equal distances are broken by lower index, so no answer depends on the tree's shape; a
// clustered set or far outliers cost depth, never a scan of the whole set per query.
class NearestPointIndex {
 public:
  explicit NearestPointIndex(const std::vector<Point3>& points);
  // The same, polling `cancel` about every kCancelPollInterval points of partitioning work (a
  // million points take ~0.5 s to index): when it asks to stop, cancelled() is true and the
  // index must not be queried.
  NearestPointIndex(const std::vector<Point3>& points, const CancelCheck& cancel);
  bool cancelled() const { return cancelled_; }
  struct Hit {
    double distance;  // Euclidean; +infinity when the set is empty
    int32_t index;    // into the points given to the constructor; -1 when the set is empty
  };
  // The nearest point (the lowest index among equally near ones).
  Hit Nearest(const Point3& q) const;
  // Euclidean distance to the nearest point; +infinity when the set is empty.
  double Distance(const Point3& q) const { return Nearest(q).distance; }
  // The k points nearest to q as (squared distance, index), nearest first, equal distances by
  // lower index; point `skip` (-1: none) is left out; fewer when the set is smaller.
  void Nearest(const Point3& q, int32_t k, int32_t skip, std::vector<std::pair<double, int32_t>>* out) const;

 private:
  struct Node {
    int32_t begin = 0, end = 0;  // range of order_ (leaves)
    int32_t left = -1, right = -1;
    int32_t axis = 0;
    double split = 0;
  };
  int32_t Build(int32_t begin, int32_t end, int32_t depth);
  void SearchOne(int32_t node, const Point3& q, double* best2, int32_t* best) const;
  void Search(int32_t node, const Point3& q, size_t k, int32_t skip,
              std::vector<std::pair<double, int32_t>>* heap) const;
  std::vector<Point3> points_;  // in order_'s order
  std::vector<int32_t> order_;  // original index of each points_ entry
  std::vector<Node> nodes_;
  const CancelCheck* cancel_ = nullptr;  // during construction only
  int64_t work_since_poll_ = 0;
  bool cancelled_ = false;
};

// Every point's k nearest other points: neighbors[i * k .. i * k + k), nearest first, ties by
// lower index; k is min(k, n - 1). Deterministic (one thread, no hashing).
struct KnnGraph {
  int32_t k = 0;
  std::vector<int32_t> neighbors;
  const int32_t* Of(size_t i) const { return neighbors.data() + i * static_cast<size_t>(k); }
};
KnnGraph NearestNeighbors(const std::vector<Point3>& points, int32_t k);
// The same, polling `cancel` while indexing and every kCancelPollInterval queries.
StatusOr<KnnGraph> NearestNeighbors(const std::vector<Point3>& points, int32_t k, const CancelCheck& cancel);

}  // namespace silk
