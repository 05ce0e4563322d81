// SPDX-License-Identifier: MIT
// Output verdicts: a closed tetrahedron is watertight and oriented; removing a face opens it;
// flipping one face breaks orientation; a fin edge breaks manifoldness. Smooth normals point out.
#include <gtest/gtest.h>

#include "mesh/mesh_checks.h"
#include "mesh/vertex_normals.h"

namespace silk {
namespace {

IoMesh Tetra() {
  IoMesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  m.triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  return m;
}

TEST(MeshChecks, Verdicts) {
  MeshVerdicts v = CheckMesh(Tetra());
  EXPECT_TRUE(v.edge_manifold && v.watertight && v.consistently_oriented);
  IoMesh open = Tetra();
  open.triangles.pop_back();
  v = CheckMesh(open);
  EXPECT_TRUE(v.edge_manifold && v.consistently_oriented);
  EXPECT_FALSE(v.watertight);
  EXPECT_EQ(v.boundary_edges, 3);
  IoMesh flipped = Tetra();
  std::swap(flipped.triangles[0][1], flipped.triangles[0][2]);
  EXPECT_FALSE(CheckMesh(flipped).consistently_oriented);
  IoMesh fin = Tetra();
  fin.positions.push_back({1, 1, 1});
  fin.triangles.push_back({1, 2, 4});
  v = CheckMesh(fin);
  EXPECT_FALSE(v.edge_manifold);
  EXPECT_EQ(v.nonmanifold_edges, 1);
  EXPECT_FALSE(CheckMesh(IoMesh{}).watertight);
}

TEST(VertexNormals, PointOutOfAClosedMesh) {
  const IoMesh m = Tetra();
  const auto n = SmoothVertexNormals(m);
  ASSERT_EQ(n.size(), 4u);
  for (int i = 1; i < 4; ++i) {
    const double dot = n[i][0] * (m.positions[i][0] - 0.25) + n[i][1] * (m.positions[i][1] - 0.25) +
                       n[i][2] * (m.positions[i][2] - 0.25);
    EXPECT_GT(dot, 0) << i;
    EXPECT_NEAR(n[i][0] * n[i][0] + n[i][1] * n[i][1] + n[i][2] * n[i][2], 1.0, 1e-12);
  }
  IoMesh lonely = m;
  lonely.positions.push_back({3, 3, 3});
  EXPECT_EQ(SmoothVertexNormals(lonely)[4], (std::array<double, 3>{0, 0, 1}));
}

}  // namespace
}  // namespace silk
