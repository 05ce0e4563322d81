// SPDX-License-Identifier: MIT
// k-d tree construction (nth_element medians, a total order on (coordinate, index)), the
// nearest-point and bounded-heap k-nearest searches with plane pruning.
#include "mesh/nearest_points.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

namespace silk {

namespace {
constexpr int32_t kLeafSize = 8;
constexpr double kInf = std::numeric_limits<double>::infinity();

double Dist2(const Point3& a, const Point3& b) {
  const double dx = a[0] - b[0], dy = a[1] - b[1], dz = a[2] - b[2];
  return dx * dx + dy * dy + dz * dz;
}
}  // namespace

NearestPointIndex::NearestPointIndex(const std::vector<Point3>& points) : NearestPointIndex(points, CancelCheck{}) {}

NearestPointIndex::NearestPointIndex(const std::vector<Point3>& points, const CancelCheck& cancel)
    : points_(points), order_(points.size()), cancel_(&cancel) {
  std::iota(order_.begin(), order_.end(), 0);
  if (!points_.empty()) {
    nodes_.reserve(2 * points_.size() / kLeafSize + 2);
    Build(0, static_cast<int32_t>(points_.size()), 0);
  }
  cancel_ = nullptr;
  if (cancelled_) {  // an unusable partial tree: drop it
    nodes_.clear();
    nodes_.shrink_to_fit();
    points_.clear();
    order_.clear();
    return;
  }
  std::vector<Point3> sorted(order_.size());
  for (size_t i = 0; i < order_.size(); ++i) sorted[i] = points[order_[i]];
  points_.swap(sorted);
}

// Splits order_[begin, end) at its median along the widest axis; points_ is still in input order.
int32_t NearestPointIndex::Build(int32_t begin, int32_t end, int32_t depth) {
  const int32_t id = static_cast<int32_t>(nodes_.size());
  nodes_.push_back(Node{begin, end});
  if (end - begin <= kLeafSize || depth > 60 || cancelled_) return id;
  work_since_poll_ += end - begin;  // the partition below is linear in the node's size
  if (work_since_poll_ >= kCancelPollInterval) {
    work_since_poll_ = 0;
    if (CancelRequested(*cancel_)) {
      cancelled_ = true;
      return id;
    }
  }
  Point3 lo = points_[order_[begin]], hi = lo;
  for (int32_t i = begin + 1; i < end; ++i)
    for (int a = 0; a < 3; ++a) {
      lo[a] = std::min(lo[a], points_[order_[i]][a]);
      hi[a] = std::max(hi[a], points_[order_[i]][a]);
    }
  int32_t axis = 0;
  for (int a = 1; a < 3; ++a)
    if (hi[a] - lo[a] > hi[axis] - lo[axis]) axis = a;
  const int32_t mid = begin + (end - begin) / 2;
  std::nth_element(order_.begin() + begin, order_.begin() + mid, order_.begin() + end, [&](int32_t x, int32_t y) {
    const double cx = points_[x][axis], cy = points_[y][axis];
    return cx < cy || (cx == cy && x < y);
  });
  const double split = points_[order_[mid]][axis];
  const int32_t left = Build(begin, mid, depth + 1);
  const int32_t right = Build(mid, end, depth + 1);
  Node& n = nodes_[id];
  n.left = left, n.right = right, n.axis = axis, n.split = split;
  return id;
}

void NearestPointIndex::SearchOne(int32_t node, const Point3& q, double* best2, int32_t* best) const {
  const Node& n = nodes_[node];
  if (n.left < 0) {
    for (int32_t i = n.begin; i < n.end; ++i) {
      const double d2 = Dist2(points_[i], q);
      if (d2 < *best2 || (d2 == *best2 && order_[i] < *best)) *best2 = d2, *best = order_[i];
    }
    return;
  }
  const double diff = q[n.axis] - n.split;
  SearchOne(diff < 0 ? n.left : n.right, q, best2, best);
  if (diff * diff <= *best2) SearchOne(diff < 0 ? n.right : n.left, q, best2, best);
}

NearestPointIndex::Hit NearestPointIndex::Nearest(const Point3& q) const {
  if (nodes_.empty()) return {kInf, -1};
  double best2 = kInf;
  int32_t best = -1;
  SearchOne(0, q, &best2, &best);
  return {std::sqrt(best2), best};
}

void NearestPointIndex::Search(int32_t node, const Point3& q, size_t k, int32_t skip,
                               std::vector<std::pair<double, int32_t>>* heap) const {
  const Node& n = nodes_[node];
  if (n.left < 0) {
    for (int32_t i = n.begin; i < n.end; ++i) {
      if (order_[i] == skip) continue;
      const std::pair<double, int32_t> c{Dist2(points_[i], q), order_[i]};
      if (heap->size() < k) {
        heap->push_back(c);
        std::push_heap(heap->begin(), heap->end());
      } else if (c < heap->front()) {
        std::pop_heap(heap->begin(), heap->end());
        heap->back() = c;
        std::push_heap(heap->begin(), heap->end());
      }
    }
    return;
  }
  const double diff = q[n.axis] - n.split;
  Search(diff < 0 ? n.left : n.right, q, k, skip, heap);
  // The far side can still hold a point as near as the worst kept (ties by index count too).
  if (heap->size() < k || diff * diff <= heap->front().first) Search(diff < 0 ? n.right : n.left, q, k, skip, heap);
}

void NearestPointIndex::Nearest(const Point3& q, int32_t k, int32_t skip,
                                std::vector<std::pair<double, int32_t>>* out) const {
  out->clear();
  if (nodes_.empty() || k <= 0) return;
  Search(0, q, static_cast<size_t>(k), skip, out);
  std::sort_heap(out->begin(), out->end());
}

KnnGraph NearestNeighbors(const std::vector<Point3>& points, int32_t k) {
  return NearestNeighbors(points, k, CancelCheck{}).value();
}

StatusOr<KnnGraph> NearestNeighbors(const std::vector<Point3>& points, int32_t k, const CancelCheck& cancel) {
  KnnGraph g;
  const int64_t n = static_cast<int64_t>(points.size());
  g.k = static_cast<int32_t>(std::max<int64_t>(0, std::min<int64_t>(k, n - 1)));
  if (g.k == 0) return g;
  const NearestPointIndex tree(points, cancel);
  if (tree.cancelled()) return CancelledStatus("normal estimation (neighbours)");
  g.neighbors.resize(static_cast<size_t>(n) * g.k);
  std::vector<std::pair<double, int32_t>> found;
  for (int64_t i = 0; i < n; ++i) {
    if ((i + 1) % kCancelPollInterval == 0 && CancelRequested(cancel))
      return CancelledStatus("normal estimation (neighbours)");
    tree.Nearest(points[i], g.k, static_cast<int32_t>(i), &found);
    for (int32_t j = 0; j < g.k; ++j) g.neighbors[i * g.k + j] = found[j].second;
  }
  return g;
}

}  // namespace silk
