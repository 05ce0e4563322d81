// SPDX-License-Identifier: MIT
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

// Each face's part, or -1 where the face has a vertex or a part out of range (left alone).
std::vector<int32_t> CheckedParts(size_t vertices, const std::vector<std::array<int32_t, 3>>& faces,
                                  const std::vector<int32_t>& face_part, int32_t parts) {
  std::vector<int32_t> out(faces.size(), -1);
  const auto n = static_cast<int64_t>(vertices);
  for (size_t f = 0; f < faces.size() && f < face_part.size(); ++f) {
    bool ok = face_part[f] >= 0 && face_part[f] < parts;
    for (int32_t v : faces[f]) ok = ok && v >= 0 && v < n;
    if (ok) out[f] = face_part[f];
  }
  return out;
}

// Per part: the sum over its faces of area * cos(face normal, nearest reference normal).
// One nearest-point query per face; a query far inside a closed cloud (a sphere's centre) visits
// every point, so `cancel` is polled before each.
StatusOr<std::vector<double>> PartVotes(const std::vector<Point3>& positions,
                                        const std::vector<std::array<int32_t, 3>>& faces,
                                        const std::vector<int32_t>& part_of, int32_t parts,
                                        const OrientedPointSet& reference, const CancelCheck& cancel) {
  std::vector<double> vote(static_cast<size_t>(parts), 0.0);
  for (size_t f = 0; f < faces.size(); ++f) {
    if (CancelRequested(cancel)) return CancelledStatus("orientation");
    if (part_of[f] < 0) continue;
    const auto& t = faces[f];
    const Point3 &a = positions[t[0]], &b = positions[t[1]], &c = positions[t[2]];
    // |cross| = 2 * area, so dot(cross, m) / 2 = area * dot(unit normal, m).
    const Point3 doubled_area_normal = Cross(Sub(b, a), Sub(c, a));
    const Point3 centroid{(a[0] + b[0] + c[0]) / 3, (a[1] + b[1] + c[1]) / 3, (a[2] + b[2] + c[2]) / 3};
    const Point3 m = reference.NormalNear(centroid);
    const double len = std::sqrt(Dot(m, m));
    if (!(len > 0)) continue;
    vote[static_cast<size_t>(part_of[f])] += 0.5 * Dot(doubled_area_normal, m) / len;
  }
  return vote;
}
}  // namespace

OrientedPointSet::OrientedPointSet(std::vector<Point3> positions, std::vector<Point3> normals)
    : OrientedPointSet(std::move(positions), std::move(normals), CancelCheck{}) {}

OrientedPointSet::OrientedPointSet(std::vector<Point3> positions, std::vector<Point3> normals,
                                   const CancelCheck& cancel)
    : normals_(std::move(normals)), index_(positions, cancel) {
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
  return OrientPartsToPoints(positions, faces, face_part, parts, reference, CancelCheck{}).value();
}

StatusOr<PartOrientationReport> OrientPartsToPoints(const std::vector<Point3>& positions,
                                                    std::vector<std::array<int32_t, 3>>* faces,
                                                    const std::vector<int32_t>& face_part, int32_t parts,
                                                    const OrientedPointSet& reference, const CancelCheck& cancel) {
  PartOrientationReport report;
  if (parts <= 0 || reference.empty()) return report;
  const std::vector<int32_t> part_of = CheckedParts(positions.size(), *faces, face_part, parts);
  SILK_ASSIGN_OR_RETURN(const std::vector<double> vote,
                        PartVotes(positions, *faces, part_of, parts, reference, cancel));
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
    if (part_of[f] >= 0 && flip[static_cast<size_t>(part_of[f])]) std::swap((*faces)[f][1], (*faces)[f][2]);
  return report;
}

}  // namespace silk
