// SPDX-License-Identifier: MIT
// Part orientation from reference normals: outward parts are kept, inward ones reversed, each
// part decided on its own, reversed reference normals reverse the verdict, zero-area parts and
// faces with bad indices are left alone. The check of the result is independent of the vote:
// on convex parts centred at known points, outward means dot(face normal, centroid - centre) > 0.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <vector>

#include "mesh/orient_to_points.h"

namespace silk {
namespace {

using Face = std::array<int32_t, 3>;

// An octahedron around `centre` with radius r, faces wound outward; appended to positions/faces.
void AddOctahedron(const Point3& centre, double r, int32_t part, bool inward, std::vector<Point3>* positions,
                   std::vector<Face>* faces, std::vector<int32_t>* face_part) {
  const auto base = static_cast<int32_t>(positions->size());
  const Point3 dirs[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  for (const Point3& d : dirs) positions->push_back({centre[0] + r * d[0], centre[1] + r * d[1], centre[2] + r * d[2]});
  // +x=0 -x=1 +y=2 -y=3 +z=4 -z=5; counter-clockwise seen from outside.
  const Face outward[8] = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4}, {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
  for (Face f : outward) {
    if (inward) std::swap(f[1], f[2]);
    faces->push_back({base + f[0], base + f[1], base + f[2]});
    face_part->push_back(part);
  }
}

// Points on the sphere around `centre` with outward (or inward) unit normals.
void AddSpherePoints(const Point3& centre, double r, bool inward_normals, std::vector<Point3>* pos,
                     std::vector<Point3>* nrm) {
  for (int i = 0; i < 24; ++i)
    for (int j = 1; j < 12; ++j) {
      const double th = 2 * M_PI * i / 24, ph = M_PI * j / 12;
      const Point3 d{std::cos(th) * std::sin(ph), std::sin(th) * std::sin(ph), std::cos(ph)};
      pos->push_back({centre[0] + r * d[0], centre[1] + r * d[1], centre[2] + r * d[2]});
      const double s = inward_normals ? -1 : 1;
      nrm->push_back({s * d[0], s * d[1], s * d[2]});
    }
}

// Independent verdict: +1 every face of the part points away from `centre`, -1 every face
// towards it, 0 mixed.
int Facing(const std::vector<Point3>& p, const std::vector<Face>& faces, const std::vector<int32_t>& part,
           int32_t which, const Point3& centre) {
  int out = 0, in = 0;
  for (size_t f = 0; f < faces.size(); ++f) {
    if (part[f] != which) continue;
    const Point3 &a = p[faces[f][0]], &b = p[faces[f][1]], &c = p[faces[f][2]];
    const Point3 u{b[0] - a[0], b[1] - a[1], b[2] - a[2]}, v{c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    const Point3 n{u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
    const Point3 w{(a[0] + b[0] + c[0]) / 3 - centre[0], (a[1] + b[1] + c[1]) / 3 - centre[1],
                   (a[2] + b[2] + c[2]) / 3 - centre[2]};
    (n[0] * w[0] + n[1] * w[1] + n[2] * w[2] > 0 ? out : in)++;
  }
  return in == 0 ? 1 : out == 0 ? -1 : 0;
}

struct Scene {
  std::vector<Point3> positions;
  std::vector<Face> faces;
  std::vector<int32_t> part;
  std::vector<Point3> ref_pos, ref_nrm;
};

const Point3 kA{-2, 0, 0}, kB{2, 0.5, 0};

Scene TwoParts(bool a_inward, bool b_inward, bool reference_inward) {
  Scene s;
  AddOctahedron(kA, 1.0, 0, a_inward, &s.positions, &s.faces, &s.part);
  AddOctahedron(kB, 0.8, 1, b_inward, &s.positions, &s.faces, &s.part);
  AddSpherePoints(kA, 1.0, reference_inward, &s.ref_pos, &s.ref_nrm);
  AddSpherePoints(kB, 0.8, reference_inward, &s.ref_pos, &s.ref_nrm);
  return s;
}

TEST(OrientToPoints, OutwardPartsAreKeptAndInwardOnesReversed) {
  for (int mask = 0; mask < 4; ++mask) {
    Scene s = TwoParts(mask & 1, mask & 2, false);
    const auto before = s.faces;
    const PartOrientationReport r =
        OrientPartsToPoints(s.positions, &s.faces, s.part, 2, OrientedPointSet(s.ref_pos, s.ref_nrm));
    EXPECT_EQ(r.parts_flipped, ((mask & 1) ? 1 : 0) + ((mask & 2) ? 1 : 0)) << mask;
    EXPECT_EQ(r.parts_undecided, 0);
    EXPECT_EQ(Facing(s.positions, s.faces, s.part, 0, kA), 1) << mask;
    EXPECT_EQ(Facing(s.positions, s.faces, s.part, 1, kB), 1) << mask;
    for (size_t f = 0; f < s.faces.size(); ++f) {  // same corners, same first corner
      EXPECT_EQ(s.faces[f][0], before[f][0]);
      const bool flipped = s.part[f] == 0 ? (mask & 1) : (mask & 2);
      EXPECT_EQ(s.faces[f][1], flipped ? before[f][2] : before[f][1]);
    }
  }
}

TEST(OrientToPoints, ReversedReferenceNormalsReverseTheVerdict) {
  Scene s = TwoParts(false, true, true);
  const PartOrientationReport r =
      OrientPartsToPoints(s.positions, &s.faces, s.part, 2, OrientedPointSet(s.ref_pos, s.ref_nrm));
  EXPECT_EQ(r.parts_flipped, 1);
  EXPECT_EQ(Facing(s.positions, s.faces, s.part, 0, kA), -1);
  EXPECT_EQ(Facing(s.positions, s.faces, s.part, 1, kB), -1);
}

TEST(OrientToPoints, ZeroAreaPartsBadIndicesAndEmptyReferenceAreLeftAlone) {
  Scene s = TwoParts(true, false, false);
  // Part 2: a zero-area face (three collinear points); part 7 (outside [0, parts)); a face with an
  // index past the positions.
  const auto n = static_cast<int32_t>(s.positions.size());
  s.positions.push_back({0, 0, 0});
  s.positions.push_back({0.1, 0, 0});
  s.positions.push_back({0.2, 0, 0});
  s.faces.push_back({n, n + 1, n + 2});
  s.part.push_back(2);
  s.faces.push_back({0, 2, 4});
  s.part.push_back(7);
  s.faces.push_back({0, 2, n + 50});
  s.part.push_back(0);
  const auto tail = std::vector<Face>(s.faces.end() - 3, s.faces.end());
  const PartOrientationReport r =
      OrientPartsToPoints(s.positions, &s.faces, s.part, 3, OrientedPointSet(s.ref_pos, s.ref_nrm));
  EXPECT_EQ(r.parts_flipped, 1);
  EXPECT_EQ(r.parts_undecided, 1);
  EXPECT_EQ(std::vector<Face>(s.faces.end() - 3, s.faces.end()), tail);

  Scene t = TwoParts(true, true, false);
  const auto before = t.faces;
  EXPECT_EQ(OrientPartsToPoints(t.positions, &t.faces, t.part, 2, OrientedPointSet({}, {})).parts_flipped, 0);
  EXPECT_EQ(OrientPartsToPoints(t.positions, &t.faces, t.part, 2, OrientedPointSet(t.ref_pos, {})).parts_flipped, 0);
  EXPECT_EQ(t.faces, before);
}

}  // namespace
}  // namespace silk
