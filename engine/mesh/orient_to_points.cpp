// Part orientation by area-weighted normal votes against the nearest reference point.
#include "mesh/orient_to_points.h"

#include <cmath>
#include <utility>

namespace silk {

namespace {
Point3 Sub(const Point3& a, const Point3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
Point3 Cross(const Point3& a, const Point3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
double Dot(const Point3& a, const Point3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
}  // namespace

OrientedPointSet::OrientedPointSet(std::vector<Point3> positions, std::vector<Point3> normals)
    : normals_(std::move(normals)), index_(positions) {
  if (positions.size() != normals_.size()) normals_.clear();
}

Point3 OrientedPointSet::NormalNear(const Point3& q) const {
  if (normals_.empty()) return {0, 0, 0};
  const NearestPointIndex::Hit hit = index_.Nearest(q);
  return hit.index < 0 ? Point3{0, 0, 0} : normals_[static_cast<size_t>(hit.index)];
}

PartOrientationReport OrientPartsToPoints(const std::vector<Point3>& positions,
                                          std::vector<std::array<int32_t, 3>>* faces,
                                          const std::vector<int32_t>& face_part, int32_t parts,
                                          const OrientedPointSet& reference) {
  PartOrientationReport report;
  if (parts <= 0 || reference.empty()) return report;
  std::vector<double> vote(static_cast<size_t>(parts), 0.0);
  const auto n = static_cast<int64_t>(positions.size());
  auto valid = [&](size_t f) {
    if (f >= face_part.size() || face_part[f] < 0 || face_part[f] >= parts) return false;
    for (int32_t v : (*faces)[f])
      if (v < 0 || v >= n) return false;
    return true;
  };
  for (size_t f = 0; f < faces->size(); ++f) {
    if (!valid(f)) continue;
    const auto& t = (*faces)[f];
    const Point3 &a = positions[t[0]], &b = positions[t[1]], &c = positions[t[2]];
    // |cross| = 2 * area, so dot(cross, m) / 2 = area * dot(unit normal, m).
    const Point3 doubled_area_normal = Cross(Sub(b, a), Sub(c, a));
    const Point3 centroid{(a[0] + b[0] + c[0]) / 3, (a[1] + b[1] + c[1]) / 3, (a[2] + b[2] + c[2]) / 3};
    Point3 m = reference.NormalNear(centroid);
    const double len = std::sqrt(Dot(m, m));
    if (!(len > 0)) continue;
    vote[static_cast<size_t>(face_part[f])] += 0.5 * Dot(doubled_area_normal, m) / len;
  }
  std::vector<char> flip(static_cast<size_t>(parts), 0);
  for (int32_t p = 0; p < parts; ++p) {
    if (vote[p] < 0) {
      flip[p] = 1;
      ++report.parts_flipped;
    } else if (vote[p] == 0) {
      ++report.parts_undecided;
    }
  }
  for (size_t f = 0; f < faces->size(); ++f)
    if (valid(f) && flip[static_cast<size_t>(face_part[f])]) std::swap((*faces)[f][1], (*faces)[f][2]);
  return report;
}

}  // namespace silk
