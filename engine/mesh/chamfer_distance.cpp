// Chamfer distance: grid nearest-neighbour index, mean distances both ways, mesh samples.
#include "mesh/chamfer_distance.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "mesh/surface_sampling.h"

namespace silk {

namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();
}  // namespace

NearestPointIndex::NearestPointIndex(const std::vector<Point3>& points) {
  if (points.empty()) return;
  Point3 lo = points[0], hi = points[0];
  for (const Point3& p : points)
    for (int a = 0; a < 3; ++a) lo[a] = std::min(lo[a], p[a]), hi[a] = std::max(hi[a], p[a]);
  const double extent = std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2], 1e-12});
  // About two points per cell if they filled the box; surfaces fill fewer cells, denser.
  cell_ = extent / std::max(1.0, std::cbrt(points.size() / 2.0));
  origin_ = lo;
  for (int a = 0; a < 3; ++a) dims_[a] = std::min(1024, 1 + static_cast<int32_t>((hi[a] - lo[a]) / cell_));
  const size_t cells = static_cast<size_t>(dims_[0]) * dims_[1] * dims_[2];
  std::vector<int32_t> cell_of(points.size());
  cell_start_.assign(cells + 1, 0);
  for (size_t i = 0; i < points.size(); ++i) {
    const auto c = CellOf(points[i]);
    cell_of[i] = (c[0] * dims_[1] + c[1]) * dims_[2] + c[2];
    ++cell_start_[cell_of[i] + 1];
  }
  for (size_t c = 0; c < cells; ++c) cell_start_[c + 1] += cell_start_[c];
  points_.resize(points.size());
  ids_.resize(points.size());
  std::vector<int32_t> fill(cell_start_.begin(), cell_start_.end() - 1);
  for (size_t i = 0; i < points.size(); ++i) {
    const int32_t slot = fill[cell_of[i]]++;
    points_[slot] = points[i];
    ids_[slot] = static_cast<int32_t>(i);
  }
}

std::array<int32_t, 3> NearestPointIndex::CellOf(const Point3& q) const {
  std::array<int32_t, 3> c{};
  for (int a = 0; a < 3; ++a) {
    const double t = std::floor((q[a] - origin_[a]) / cell_);
    c[a] = t < 0 ? 0 : t >= dims_[a] ? dims_[a] - 1 : static_cast<int32_t>(t);
  }
  return c;
}

void NearestPointIndex::ScanCell(int32_t x, int32_t y, int32_t z, const Point3& q, double* best2,
                                 int32_t* best) const {
  const int32_t c = (x * dims_[1] + y) * dims_[2] + z;
  for (int32_t i = cell_start_[c]; i < cell_start_[c + 1]; ++i) {
    const Point3& p = points_[i];
    const double dx = p[0] - q[0], dy = p[1] - q[1], dz = p[2] - q[2];
    const double d2 = dx * dx + dy * dy + dz * dz;
    if (d2 < *best2 || (d2 == *best2 && ids_[i] < *best)) *best2 = d2, *best = ids_[i];
  }
}

NearestPointIndex::Hit NearestPointIndex::Nearest(const Point3& q) const {
  if (points_.empty()) return {kInf, -1};
  const auto c = CellOf(q);
  const int32_t max_ring = std::max({dims_[0], dims_[1], dims_[2]});
  double best2 = kInf;
  int32_t best = -1;
  // Ring r holds the cells at Chebyshev distance r from the query's (clamped) cell; every
  // point in ring r + 1 or beyond is at least r * cell_ from the query.
  for (int32_t r = 0; r <= max_ring; ++r) {
    for (int32_t x = std::max(0, c[0] - r); x <= std::min(dims_[0] - 1, c[0] + r); ++x)
      for (int32_t y = std::max(0, c[1] - r); y <= std::min(dims_[1] - 1, c[1] + r); ++y) {
        const bool x_or_y_edge = std::abs(x - c[0]) == r || std::abs(y - c[1]) == r;
        if (x_or_y_edge) {
          for (int32_t z = std::max(0, c[2] - r); z <= std::min(dims_[2] - 1, c[2] + r); ++z)
            ScanCell(x, y, z, q, &best2, &best);
        } else {
          if (c[2] - r >= 0) ScanCell(x, y, c[2] - r, q, &best2, &best);
          if (r > 0 && c[2] + r < dims_[2]) ScanCell(x, y, c[2] + r, q, &best2, &best);
        }
      }
    const double reach = r * cell_;
    if (best2 < reach * reach) break;
  }
  return {std::sqrt(best2), best};
}

namespace {
// The mean distance, summed in the same order whether or not `cancel` is polled (same value).
StatusOr<double> MeanDistance(const std::vector<Point3>& from, const NearestPointIndex& to,
                              const CancelCheck& cancel) {
  if (from.empty()) return kInf;
  double sum = 0;
  for (size_t i = 0; i < from.size(); ++i) {
    if ((i + 1) % kChamferPollInterval == 0 && CancelRequested(cancel)) return CancelledStatus("scoring");
    sum += to.Distance(from[i]);
  }
  return sum / static_cast<double>(from.size());
}
}  // namespace

StatusOr<ChamferDistance> PointSetChamfer(const std::vector<Point3>& a, const std::vector<Point3>& b,
                                          const CancelCheck& cancel) {
  ChamferDistance d;
  SILK_ASSIGN_OR_RETURN(d.a_to_b, MeanDistance(a, NearestPointIndex(b), cancel));
  if (CancelRequested(cancel)) return CancelledStatus("scoring");
  SILK_ASSIGN_OR_RETURN(d.b_to_a, MeanDistance(b, NearestPointIndex(a), cancel));
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
