// SPDX-License-Identifier: MIT
// Vertex fans: a closed tetrahedron and an open fan have one fan per vertex; two triangles
// touching at one vertex (a bowtie) have two there, the verdict says so, and the split gives
// that vertex one copy, after which every vertex has one fan and edges are unchanged.
#include <gtest/gtest.h>

#include "mesh/mesh_checks.h"
#include "mesh/vertex_fans.h"

namespace silk {
namespace {

TEST(VertexFans, TetrahedronAndOpenFanAreManifold) {
  const std::vector<std::array<int32_t, 3>> tetra = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  VertexFans f = ComputeVertexFans(tetra, 4);
  EXPECT_EQ(f.nonmanifold_vertices, 0);
  EXPECT_EQ(f.fans_per_vertex, (std::vector<int32_t>{1, 1, 1, 1}));
  const std::vector<std::array<int32_t, 3>> fan = {{0, 1, 2}, {0, 2, 3}, {0, 3, 4}};
  f = ComputeVertexFans(fan, 6);  // vertex 5 has no face
  EXPECT_EQ(f.fans_per_vertex, (std::vector<int32_t>{1, 1, 1, 1, 1, 0}));
}

TEST(VertexFans, BowtieIsFoundAndSplit) {
  std::vector<std::array<int32_t, 3>> faces = {{0, 1, 2}, {0, 3, 4}, {0, 2, 5}};
  VertexFans f = ComputeVertexFans(faces, 6);
  EXPECT_EQ(f.nonmanifold_vertices, 1);
  EXPECT_EQ(f.fans_per_vertex[0], 2);
  EXPECT_EQ(f.corner_fan[0], 0);  // face 0 at vertex 0: fan 0
  EXPECT_EQ(f.corner_fan[3], 1);  // face 1: the other fan
  EXPECT_EQ(f.corner_fan[6], 0);  // face 2 shares edge 0-2 with face 0
  IoMesh m;
  m.positions.resize(6);
  m.triangles = faces;
  MeshVerdicts v = CheckMesh(m);
  EXPECT_TRUE(v.edge_manifold && v.consistently_oriented);
  EXPECT_FALSE(v.vertex_manifold);
  EXPECT_EQ(v.nonmanifold_vertices, 1);

  std::vector<int32_t> copy_of;
  EXPECT_EQ(SplitNonManifoldFans(&faces, 6, &copy_of), 1);
  EXPECT_EQ(copy_of, (std::vector<int32_t>{0}));
  EXPECT_EQ(faces, (std::vector<std::array<int32_t, 3>>{{0, 1, 2}, {6, 3, 4}, {0, 2, 5}}));
  m.positions.resize(7);
  m.triangles = faces;
  v = CheckMesh(m);
  EXPECT_TRUE(v.vertex_manifold && v.edge_manifold && v.consistently_oriented);
  EXPECT_EQ(v.boundary_edges, 7);
}

TEST(VertexFans, ThreeFansGetTwoCopies) {
  std::vector<std::array<int32_t, 3>> faces = {{0, 1, 2}, {0, 3, 4}, {0, 5, 6}};
  std::vector<int32_t> copy_of;
  EXPECT_EQ(SplitNonManifoldFans(&faces, 7, &copy_of), 1);
  EXPECT_EQ(copy_of, (std::vector<int32_t>{0, 0}));
  EXPECT_EQ(ComputeVertexFans(faces, 9).nonmanifold_vertices, 0);
}

}  // namespace
}  // namespace silk
