// SPDX-License-Identifier: MIT
// Which side of each generated part faces outward, decided by the input's normals: the grammar
// makes every part consistently oriented, but the sign of that orientation is the model's
// choice (a coin toss for a weak one), and renderers (back-face culling), slicers and booleans
// all read the winding as "outside".
#pragma once
#include <array>
#include <cstdint>
#include <vector>

#include "mesh/chamfer_distance.h"

namespace silk {

// Oriented reference points (the encoder's input: positions with unit normals) and a
// nearest-point index over them, built once per input.
class OrientedPointSet {
 public:
  // positions.size() == normals.size(); normals need not be unit (only their direction counts).
  OrientedPointSet(std::vector<Point3> positions, std::vector<Point3> normals);
  // The same, polling `cancel` while indexing (NearestPointIndex): cancelled() then says so and
  // the set must not be used.
  OrientedPointSet(std::vector<Point3> positions, std::vector<Point3> normals, const CancelCheck& cancel);
  bool cancelled() const { return index_.cancelled(); }
  bool empty() const { return normals_.empty(); }
  // The normal of the point nearest to q (zero vector when the set is empty).
  Point3 NormalNear(const Point3& q) const;

 private:
  std::vector<Point3> normals_;
  NearestPointIndex index_;
};

struct PartOrientationReport {
  int32_t parts_flipped = 0;    // parts whose every face's winding was reversed
  int32_t parts_undecided = 0;  // parts with no vote (no face of positive area): left as they are
};

// For each part p (face_part[f] in [0, parts)), the vote
//   sum over its faces f of  area(f) * dot(unit normal of f, normal of the reference point
//                                                            nearest to the centroid of f)
// is the area-weighted agreement of the part's winding with the input's normals; a part whose
// vote is negative has every face reversed (two corners swapped), so it agrees afterwards. A
// vote of exactly zero (no face of positive area) leaves the part as it is. Faces keep their
// order and vertices their positions; only windings change. Faces with a part index outside
// [0, parts) are left alone.
PartOrientationReport OrientPartsToPoints(const std::vector<Point3>& positions,
                                          std::vector<std::array<int32_t, 3>>* faces,
                                          const std::vector<int32_t>& face_part, int32_t parts,
                                          const OrientedPointSet& reference);
// The same, polling `cancel` before each face's query (one far inside a closed cloud visits every
// point: a million take milliseconds): kCancelled leaves the faces as they were.
StatusOr<PartOrientationReport> OrientPartsToPoints(const std::vector<Point3>& positions,
                                                    std::vector<std::array<int32_t, 3>>* faces,
                                                    const std::vector<int32_t>& face_part, int32_t parts,
                                                    const OrientedPointSet& reference, const CancelCheck& cancel);

}  // namespace silk
