// SPDX-License-Identifier: MIT
// OBJ reader: accepted statement forms, index rules, raw (unwelded) output, error messages.
#include "io/obj/obj_reader.h"

#include <gtest/gtest.h>

#include "io/mesh_reader.h"
#include "io/io_test_util.h"

namespace silk {
namespace {

TEST(ObjReader, ReadsVerticesFacesAndIgnoresAttributes) {
  const char* text =
      "# comment\n"
      "mtllib x.mtl\no thing\ng grp\n"
      "v 0 0 0\nv 1 0 0\r\nv 0 1 0 1.0\nv 0 0 1\n"
      "vt 0 0\nvt 1 0\nvt 0 1\nvn 0 0 1\n"
      "usemtl m\ns off\n"
      "f 1/1/1 2/2/1 3/3/1\n"
      "f 1//1 3//1 4//1  # trailing comment\n"
      "f 2/1 3/2 4/3\n";
  auto m = ReadObj(text, "t.obj");
  ASSERT_TRUE(m.ok()) << m.status().ToString();
  ASSERT_EQ(m->positions.size(), 4u);
  ASSERT_EQ(m->triangles.size(), 3u);
  EXPECT_EQ(m->triangles[0], (std::array<int32_t, 3>{0, 1, 2}));
  EXPECT_EQ(m->triangles[1], (std::array<int32_t, 3>{0, 2, 3}));
  EXPECT_EQ(m->triangles[2], (std::array<int32_t, 3>{1, 2, 3}));
  EXPECT_EQ(m->positions[1], (std::array<double, 3>{1, 0, 0}));
}

TEST(ObjReader, NegativeRelativeIndices) {
  auto m = ReadObj("v 0 0 0\nv 1 0 0\nv 0 1 0\nf -3 -2 -1\nv 5 5 5\nf -1 -2 -3\n", "n.obj");
  ASSERT_TRUE(m.ok()) << m.status().ToString();
  ASSERT_EQ(m->triangles.size(), 2u);
  EXPECT_EQ(m->triangles[0], (std::array<int32_t, 3>{0, 1, 2}));
  EXPECT_EQ(m->triangles[1], (std::array<int32_t, 3>{3, 2, 1}));
}

TEST(ObjReader, QuadsAndPolygonsAreFanTriangulated) {
  auto m = ReadObj("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv -1 1 0\nf 1 2 3 4\nf 1 2 3 4 5\n", "q.obj");
  ASSERT_TRUE(m.ok());
  ASSERT_EQ(m->triangles.size(), 5u);
  EXPECT_EQ(m->triangles[1], (std::array<int32_t, 3>{0, 2, 3}));
  EXPECT_EQ(m->triangles[4], (std::array<int32_t, 3>{0, 3, 4}));
  EXPECT_EQ(m->polygons_triangulated, 2);
}

TEST(ObjReader, KeepsDuplicatesAndUnreferencedVerticesRaw) {
  auto m = ReadObj("v 0 0 0\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 9 9 9\nf 1 3 4\nf 1 3 4\nf 2 3 4\n", "r.obj");
  ASSERT_TRUE(m.ok());
  EXPECT_EQ(m->positions.size(), 5u);
  EXPECT_EQ(m->triangles.size(), 3u);
  EXPECT_EQ(m->triangles[0], m->triangles[1]);
}

TEST(ObjReader, ExactDoubles) {
  auto m = ReadObj("v 0.1 -2.5e-3 123456.789012\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "d.obj");
  ASSERT_TRUE(m.ok());
  EXPECT_EQ(m->positions[0][0], 0.1);
  EXPECT_EQ(m->positions[0][1], -2.5e-3);
  EXPECT_EQ(m->positions[0][2], 123456.789012);
}

struct ObjBadCase {
  const char* text;
  const char* expect;  // substring of the message
};

TEST(ObjReader, ErrorsNameFileLineAndProblem) {
  const ObjBadCase cases[] = {
      {"v 0 0 0\nv 1 0 0\nf 1 2 5\n", "bad.obj:3: face index 5 out of range (2 vertices)"},
      {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n", "bad.obj:4: face index 0"},
      {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf -4 1 2\n", "bad.obj:4: face index -4 out of range"},
      {"v 0 0 0\nv 1 0 0\nf 1 2\n", "bad.obj:3: face has 2 corner(s)"},
      {"v 0 inf 0\n", "bad.obj:1: vertex 1 has a non-finite"},
      {"v 0 0\n", "bad.obj:1: vertex has fewer than 3"},
      {"v 0 0 x\n", "bad.obj:1: bad vertex coordinate 'x'"},
      {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1/2/3/4 2 3\n", "bad.obj:4: bad face corner"},
      {"v 0 0 0\n", "bad.obj: no faces"},
      {"", "bad.obj: empty file"},
      {"v 0 0 0\n\x01\x02\x03", "bad.obj:2: binary byte 0x01"},
  };
  for (const auto& c : cases) {
    auto m = ReadObj(c.text, "bad.obj");
    ASSERT_FALSE(m.ok()) << c.text;
    EXPECT_NE(m.status().message().find(c.expect), std::string::npos)
        << "message: " << m.status().message() << "\nexpected: " << c.expect;
  }
}

TEST(ObjReader, LimitsAreEnforced) {
  ReadOptions opts;
  opts.max_vertices = 2;
  auto m = ReadObj("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "lim.obj", opts);
  ASSERT_FALSE(m.ok());
  EXPECT_EQ(m.status().code(), StatusCode::kLimitExceeded);
}

TEST(ObjReader, ThroughFileDispatch) {
  testing::TempDir dir;
  std::string p = dir.Write("tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  auto m = ReadMeshFile(p);
  ASSERT_TRUE(m.ok()) << m.status().ToString();
  EXPECT_EQ(m->triangles.size(), 1u);
}

}  // namespace
}  // namespace silk
