// SPDX-License-Identifier: MIT
// The decoder's vertex-fan rule: a bowtie of two open fans is closed by one gap face when
// gaps may be closed (new edge, adjacent layers, non-zero area) and split otherwise; a gap whose
// chord already exists, or whose face would be flat, is split instead.
#include <gtest/gtest.h>

#include "decoder/vertex_fan_rules.h"
#include "mesh/mesh_checks.h"
#include "mesh/vertex_fans.h"

namespace silk {
namespace {

// Vertex 0 at the origin, fans (0,1,2) and (0,3,4) on opposite sides in the z = 0 plane.
struct Bowtie {
  std::vector<std::array<int32_t, 3>> faces = {{0, 1, 2}, {0, 3, 4}};
  std::vector<QVec> pos = {{50, 50, 50}, {60, 50, 50}, {55, 60, 50}, {40, 50, 50}, {45, 40, 50}};
  std::vector<int32_t> layer = {1, 1, 2, 1, 2};
};

TEST(VertexFanRules, GapClosedUnderRepair) {
  Bowtie b;
  std::vector<int32_t> copy_of;
  VertexFanCounts c;
  ResolveVertexFans(&b.faces, b.pos, b.layer, true, &copy_of, &c);
  EXPECT_EQ(c.nonmanifold_vertices, 1);
  EXPECT_EQ(c.gaps_closed, 1);
  EXPECT_EQ(c.vertices_split, 0);
  EXPECT_TRUE(copy_of.empty());
  ASSERT_EQ(b.faces.size(), 3u);
  // Both gaps (end 2 -> start 3, end 4 -> start 1) are 15^2 + 10^2 long; the first found wins.
  EXPECT_EQ(b.faces[2], (std::array<int32_t, 3>{0, 2, 3}));
  const MeshVerdicts v = CheckFaces(b.faces, 5);
  EXPECT_TRUE(v.vertex_manifold && v.edge_manifold && v.consistently_oriented);
}

TEST(VertexFanRules, SplitWithoutRepair) {
  Bowtie b;
  std::vector<int32_t> copy_of;
  VertexFanCounts c;
  ResolveVertexFans(&b.faces, b.pos, b.layer, false, &copy_of, &c);
  EXPECT_EQ(c.gaps_closed, 0);
  EXPECT_EQ(c.vertices_split, 1);
  EXPECT_EQ(c.vertex_copies, 1);
  EXPECT_EQ(copy_of, (std::vector<int32_t>{0}));
  EXPECT_EQ(b.faces.size(), 2u);
  EXPECT_TRUE(CheckFaces(b.faces, 6).vertex_manifold);
}

TEST(VertexFanRules, IllegalGapsAreSplit) {
  Bowtie b;
  b.layer = {1, 0, 2, 3, 3};  // gap 4 -> 1 spans three layers: not a legal chord
  b.pos[3] = {60, 70, 50};    // gap 2 -> 3: the face (0, 2, 3) would be flat (collinear corners)
  std::vector<int32_t> copy_of;
  VertexFanCounts c;
  ResolveVertexFans(&b.faces, b.pos, b.layer, true, &copy_of, &c);
  EXPECT_EQ(c.gaps_closed, 0);
  EXPECT_EQ(c.vertices_split, 1);
  EXPECT_TRUE(CheckFaces(b.faces, 6).vertex_manifold);
}

}  // namespace
}  // namespace silk
