// SPDX-License-Identifier: MIT
// PLY reader: the three encodings, property types and aliases, skipped properties and
// elements, plausibility checks before allocation, truncation errors; point clouds with normals.
#include "io/ply/ply_reader.h"

#include <gtest/gtest.h>

#include "io/io_test_util.h"

namespace silk {
namespace {

using testing::AppendBE;
using testing::AppendLE;

TEST(PlyReader, AsciiWithExtraPropertiesAndElements) {
  const char* text =
      "ply\nformat ascii 1.0\ncomment hi\nobj_info x\n"
      "element vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
      "property float nx\nproperty uchar red\nproperty list uchar float extra\n"
      "element face 2\nproperty list uchar int vertex_indices\nproperty int flags\n"
      "element edge 1\nproperty int vertex1\nproperty int vertex2\n"
      "end_header\n"
      "0 0 0 1 255 2 0.5 0.25\n1 0 0 1 0 0\n0 1 0 1 3 1 1.5\n0.1 0 1 1 4 0\n"
      "3 0 1 2 7\n4 0 1 2 3 8\n"
      "0 1\n";
  auto m = ReadPly(text, "a.ply");
  ASSERT_TRUE(m.ok()) << m.status().ToString();
  ASSERT_EQ(m->positions.size(), 4u);
  ASSERT_EQ(m->triangles.size(), 3u);
  EXPECT_EQ(m->triangles[0], (std::array<int32_t, 3>{0, 1, 2}));
  EXPECT_EQ(m->triangles[2], (std::array<int32_t, 3>{0, 2, 3}));
  // float32 property: value rounded to float as a binary file would store it.
  EXPECT_EQ(m->positions[3][0], static_cast<double>(0.1f));
}

std::string BinaryCube(bool big_endian, bool truncate_last_face = false) {
  std::string h = std::string("ply\nformat ") + (big_endian ? "binary_big_endian" : "binary_little_endian") +
                  " 1.0\n"
                  "element vertex 4\nproperty double x\nproperty int16 nx\nproperty float32 y\n"
                  "property float z\nproperty uint8 alpha\n"
                  "element material 2\nproperty list ushort char name\n"
                  "element face 2\nproperty uchar flag\nproperty list int uint vertex_index\n"
                  "end_header\n";
  auto put = [&](auto v) {
    if (big_endian)
      AppendBE(&h, v);
    else
      AppendLE(&h, v);
  };
  const double xs[4] = {0, 1, 0, 0.1};
  const float ys[4] = {0, 0, 1, 0}, zs[4] = {0, 0, 0, 1};
  for (int i = 0; i < 4; ++i) {
    put(xs[i]);
    put(int16_t{-7});
    put(ys[i]);
    put(zs[i]);
    put(uint8_t{200});
  }
  for (int m = 0; m < 2; ++m) {
    put(uint16_t{3});
    put(int8_t{'a'});
    put(int8_t{'b'});
    put(int8_t{'c'});
  }
  put(uint8_t{1});
  put(int32_t{3});
  put(uint32_t{0});
  put(uint32_t{1});
  put(uint32_t{2});
  put(uint8_t{1});
  put(int32_t{4});
  put(uint32_t{0});
  put(uint32_t{1});
  put(uint32_t{2});
  put(uint32_t{3});
  if (truncate_last_face) h.resize(h.size() - 6);
  return h;
}

TEST(PlyReader, BinaryLittleAndBigEndian) {
  for (bool be : {false, true}) {
    auto m = ReadPly(BinaryCube(be), "b.ply");
    ASSERT_TRUE(m.ok()) << be << " " << m.status().ToString();
    ASSERT_EQ(m->positions.size(), 4u);
    EXPECT_EQ(m->positions[3][0], 0.1);  // double property exact
    EXPECT_EQ(m->positions[2][1], 1.0);
    EXPECT_EQ(m->positions[3][2], 1.0);
    ASSERT_EQ(m->triangles.size(), 3u);
    EXPECT_EQ(m->triangles[1], (std::array<int32_t, 3>{0, 1, 2}));
    EXPECT_EQ(m->triangles[2], (std::array<int32_t, 3>{0, 2, 3}));
  }
}

TEST(PlyReader, TruncatedBodyNamesElementAndIndex) {
  auto m = ReadPly(BinaryCube(false, true), "t.ply");
  ASSERT_FALSE(m.ok());
  EXPECT_NE(m.status().message().find("t.ply: truncated body: face 1 of 2"), std::string::npos) << m.status().message();
}

TEST(PlyReader, HugeHeaderCountFailsWithoutAllocating) {
  std::string h =
      "ply\nformat binary_little_endian 1.0\nelement vertex 4000000000000\nproperty float x\n"
      "property float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";
  h += std::string(100, '\0');
  auto m = ReadPly(h, "huge.ply");
  ASSERT_FALSE(m.ok());
  // 100 bytes hold 8 vertices; the error names the first missing one.
  EXPECT_NE(m.status().message().find("huge.ply: truncated body: vertex 8 of 4000000000000"), std::string::npos)
      << m.status().message();
}

TEST(PlyReader, PlausibleHugeHeaderHitsTheLimitBeforeAllocating) {
  std::string h =
      "ply\nformat binary_little_endian 1.0\nelement vertex 1000\nproperty float x\n"
      "property float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";
  h += std::string(1000 * 12 + 13, '\0');
  ReadOptions opts;
  opts.max_vertices = 999;
  auto m = ReadPly(h, "lim.ply", opts);
  ASSERT_FALSE(m.ok());
  EXPECT_EQ(m.status().code(), StatusCode::kLimitExceeded);
  EXPECT_NE(m.status().message().find("lim.ply: header declares 1000 vertices (limit 999)"), std::string::npos);
}

TEST(PlyReader, HeaderAndBodyErrors) {
  struct Case {
    std::string text, expect;
  } cases[] = {
      {"ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nend_header\n0 0\n1 0\n0 1\n",
       "e.ply:3: vertex element has no property 'z'"},
      {"ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
       "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n",
       "e.ply:13: face 0: vertex index 3 out of range (3 vertices)"},
      {"ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
       "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 nan 0\n0 1 0\n3 0 1 2\n",
       "e.ply:11: vertex 1: non-finite coordinate"},
      {"ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
       "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n2 0 1\n",
       "e.ply: face 0: 2 corner(s)"},
      {"ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
       "end_header\n0 0 0\n1 0 0\n0 1 0\n",
       "e.ply: no faces"},
      {"ply\nformat binary_middle_endian 1.0\nend_header\n", "e.ply:2: unknown PLY format"},
      {"ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n", "e.ply: PLY header has no end_header"},
      {"plx\n", "e.ply: not a PLY file"},
  };
  for (const auto& c : cases) {
    auto m = ReadPly(c.text, "e.ply");
    ASSERT_FALSE(m.ok()) << c.text;
    EXPECT_NE(m.status().message().find(c.expect), std::string::npos)
        << "message: " << m.status().message() << "\nexpected: " << c.expect;
  }
}

TEST(PlyPointCloud, NormalsAndNoFaces) {
  const std::string ply =
      "ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nproperty float y\nproperty float z\n"
      "property float nx\nproperty float ny\nproperty float nz\nend_header\n0 0 0 0 0 1\n1 2 3 1 0 0\n";
  auto pc = ReadPlyPointCloud(ply, "p.ply");
  ASSERT_TRUE(pc.ok()) << pc.status().ToString();
  ASSERT_EQ(pc->normals.size(), 2u);
  EXPECT_EQ(pc->normals[1], (std::array<double, 3>{1, 0, 0}));
  EXPECT_EQ(pc->mesh.positions[1], (std::array<double, 3>{1, 2, 3}));
  EXPECT_FALSE(ReadPly(ply, "p.ply").ok());  // the mesh reader still wants faces
  const std::string no_normals =
      "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\nend_header\n1 1 "
      "1\n";
  auto pn = ReadPlyPointCloud(no_normals, "q.ply");
  ASSERT_TRUE(pn.ok());
  EXPECT_TRUE(pn->normals.empty());
  const std::string nan_normal =
      "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\n"
      "property float nx\nproperty float ny\nproperty float nz\nend_header\n0 0 0 nan 0 1\n";
  EXPECT_FALSE(ReadPlyPointCloud(nan_normal, "r.ply").ok());
}

}  // namespace
}  // namespace silk
