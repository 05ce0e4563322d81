// SPDX-License-Identifier: MIT
// Orientation to the input turns surface patches (faces joined by shared edges), not whole
// generated parts: one part holding two patches, one wound inward, gets only that patch reversed.
// The check is independent of the vote: on octahedra around known centres, outward means
// dot(face normal, centroid - centre) > 0.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <vector>

#include "runtime/input_orientation.h"
#include "tokenizer/cleanup/quantize.h"

namespace silk {
namespace {

using Face = std::array<int32_t, 3>;

// An octahedron of grid radius r around grid cell c, faces wound outward (or inward), in part 0.
void AddOctahedron(const QVec& c, int32_t r, bool inward, TokenizerDecodedMesh* m) {
  const auto base = static_cast<int32_t>(m->positions.size());
  const QVec corners[6] = {{c.x + r, c.y, c.z}, {c.x - r, c.y, c.z}, {c.x, c.y + r, c.z},
                           {c.x, c.y - r, c.z}, {c.x, c.y, c.z + r}, {c.x, c.y, c.z - r}};
  for (const QVec& q : corners) {
    m->positions.push_back(q);
    m->vertex_component.push_back(0);
  }
  const Face outward[8] = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4}, {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
  for (Face f : outward) {
    if (inward) std::swap(f[1], f[2]);
    m->faces.push_back({base + f[0], base + f[1], base + f[2]});
    m->face_component.push_back(0);
  }
}

// Encoder-style rows (xyz, unit normal; model frame) on a sphere around grid cell c, outward.
void AddSphereRows(const QVec& c, double radius, std::vector<float>* rows) {
  const std::array<double, 3> centre = DequantizePositions({c})[0];
  for (int i = 0; i < 24; ++i)
    for (int j = 1; j < 12; ++j) {
      const double th = 2 * M_PI * i / 24, ph = M_PI * j / 12;
      const double d[3] = {std::cos(th) * std::sin(ph), std::sin(th) * std::sin(ph), std::cos(ph)};
      for (int k = 0; k < 3; ++k) rows->push_back(static_cast<float>(centre[k] + radius * d[k]));
      for (int k = 0; k < 3; ++k) rows->push_back(static_cast<float>(d[k]));
    }
}

// +1: every face of faces [begin, end) points away from grid cell c; -1: every one towards it.
int Facing(const TokenizerDecodedMesh& m, size_t begin, size_t end, const QVec& c) {
  int out = 0, in = 0;
  for (size_t f = begin; f < end; ++f) {
    const QVec &a = m.positions[m.faces[f][0]], &b = m.positions[m.faces[f][1]], &d = m.positions[m.faces[f][2]];
    const int64_t u[3] = {b.x - a.x, b.y - a.y, b.z - a.z}, v[3] = {d.x - a.x, d.y - a.y, d.z - a.z};
    const int64_t n[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
    const int64_t w[3] = {a.x + b.x + d.x - 3 * c.x, a.y + b.y + d.y - 3 * c.y, a.z + b.z + d.z - 3 * c.z};
    (n[0] * w[0] + n[1] * w[1] + n[2] * w[2] > 0 ? out : in)++;
  }
  return in == 0 ? 1 : out == 0 ? -1 : 0;
}

TEST(InputOrientation, EachSurfacePatchOfAPartFacesOutOnItsOwn) {
  const QVec left{40, 64, 64}, right{88, 64, 64};
  for (int mask = 0; mask < 4; ++mask) {
    TokenizerDecodedMesh m;
    m.components = 1;  // one generated part, two patches
    AddOctahedron(left, 12, mask & 1, &m);
    AddOctahedron(right, 12, mask & 2, &m);
    int32_t patches = 0;
    const std::vector<int32_t> patch = SurfacePatches(m, &patches);
    ASSERT_EQ(patches, 2);
    for (size_t f = 0; f < 16; ++f) EXPECT_EQ(patch[f], f < 8 ? 0 : 1) << f;
    std::vector<float> rows;
    AddSphereRows(left, 12.0 / 63.5, &rows);
    AddSphereRows(right, 12.0 / 63.5, &rows);
    auto reference = MakeInputOrientation(rows);
    ASSERT_TRUE(reference.ok());
    const PartOrientationReport r = OrientToInput(&m, **reference);
    EXPECT_EQ(r.parts_flipped, (mask & 1 ? 1 : 0) + (mask & 2 ? 1 : 0)) << mask;
    EXPECT_EQ(Facing(m, 0, 8, left), 1) << mask;
    EXPECT_EQ(Facing(m, 8, 16, right), 1) << mask;
  }
}

TEST(InputOrientation, FacesSharingAnEdgeAreOnePatch) {
  TokenizerDecodedMesh m;
  m.components = 1;
  m.positions = {{0, 0, 0}, {10, 0, 0}, {0, 10, 0}, {10, 10, 0}, {20, 0, 0}, {30, 0, 0}, {20, 10, 0}};
  m.faces = {{0, 1, 2}, {1, 3, 2}, {1, 4, 3}, {4, 5, 6}};  // three joined by edges; the last shares vertex 4 only
  m.face_component.assign(4, 0);
  int32_t patches = 0;
  const std::vector<int32_t> patch = SurfacePatches(m, &patches);
  EXPECT_EQ(patches, 2);
  EXPECT_EQ(patch, (std::vector<int32_t>{0, 0, 0, 1}));
}

}  // namespace
}  // namespace silk
