// SPDX-License-Identifier: MIT
// XYZ/PTS reader: line forms (3 or 6 values, comments, CRLF, commas, the PTS count line), every
// refusal with its file and line, the vertex limit, and the file-level dispatch
// (ReadMeshOrPointCloudFile: .xyz/.pts/.ply clouds, gzip; ReadMeshFile: a cloud has no faces).
#include "io/xyz/xyz_reader.h"

#include <gtest/gtest.h>

#include "io/io_test_util.h"
#include "io/mesh_format.h"
#include "io/mesh_reader.h"
#include "io/point_cloud_reader.h"

namespace silk {
namespace {

TEST(XyzReader, PointsCommentsCrlfAndCommas) {
  auto pc = ReadXyz("# scan\r\n1 2 3\r\n\r\n  4,5,6   # trailing\n-1e-3\t0.5 7\n", "a.xyz");
  ASSERT_TRUE(pc.ok()) << pc.status().ToString();
  ASSERT_EQ(pc->mesh.positions.size(), 3u);
  EXPECT_TRUE(pc->normals.empty());
  EXPECT_TRUE(pc->mesh.triangles.empty());
  EXPECT_EQ(pc->mesh.positions[1], (std::array<double, 3>{4, 5, 6}));
  EXPECT_EQ(pc->mesh.positions[2], (std::array<double, 3>{-1e-3, 0.5, 7}));
}

TEST(XyzReader, NormalsAndPtsCountLine) {
  auto pc = ReadXyz("2\n0 0 0 0 0 1\n1 1 1 0.6 0.8 0\n", "b.pts");
  ASSERT_TRUE(pc.ok()) << pc.status().ToString();
  ASSERT_EQ(pc->normals.size(), 2u);
  EXPECT_EQ(pc->normals[1], (std::array<double, 3>{0.6, 0.8, 0}));  // as read
  EXPECT_EQ(pc->mesh.positions[1], (std::array<double, 3>{1, 1, 1}));
}

TEST(XyzReader, RefusalsNameFileAndLine) {
  struct Case {
    const char* text;
    const char* expect;
  } cases[] = {
      {"", "e.xyz: no points"},
      {"# only a comment\n\n", "e.xyz: no points"},
      {"1 2\n", "e.xyz:1: 2 values; a point line is 'x y z' or 'x y z nx ny nz'"},
      {"0 0 0\n1 2\n", "e.xyz:2: 2 values, but line 1 has 3 (every point line has the same columns)"},
      {"0 0 0 1\n", "e.xyz:1: 4 values; a point line is"},
      {"0 0 0 255 0 0 1\n", "e.xyz:1: 7 values;"},
      {"0 0 0\n0 0 0 0 0 1\n", "e.xyz:2: 6 values, but line 1 has 3"},
      {"0 0 0 255 128 0\n", "e.xyz:1: values 4-6 are not a unit normal (length 285.3)"},
      {"0 0 0 0 0 0\n", "e.xyz:1: values 4-6 are not a unit normal (length 0)"},
      {"0 0 0\n1 x 0\n", "e.xyz:2: bad number 'x'"},
      {"0 0 0\n1 nan 0\n", "e.xyz:2: non-finite value 'nan'"},
      {"0 0 0 0 0 inf\n", "e.xyz:1: non-finite value 'inf'"},
      {"3\n0 0 0\n1 1 1\n", "e.xyz:1: the count line says 3 points, the file has 2"},
      {"0 0 0\n7\n", "e.xyz:2: 1 value, but line 1 has 3"},
      {"abc\n0 0 0\n", "e.xyz:1: 1 value 'abc'"},
      {"-5\n0 0 0\n", "e.xyz:1: 1 value '-5'"},
  };
  for (const Case& c : cases) {
    auto pc = ReadXyz(c.text, "e.xyz");
    ASSERT_FALSE(pc.ok()) << "accepted: " << c.text;
    EXPECT_NE(pc.status().message().find(c.expect), std::string::npos)
        << "message: " << pc.status().message() << "\nexpected: " << c.expect;
  }
}

TEST(XyzReader, BinaryBytesAreRefused) {
  auto pc = ReadXyz(std::string("0 0 0\n1 1\0 1\n", 12), "b.xyz");
  ASSERT_FALSE(pc.ok());
  EXPECT_NE(pc.status().message().find("b.xyz: binary byte at offset 9 (not a text point cloud)"), std::string::npos)
      << pc.status().message();
}

TEST(XyzReader, VertexLimit) {
  ReadOptions opts;
  opts.max_vertices = 2;
  EXPECT_TRUE(ReadXyz("0 0 0\n1 1 1\n", "l.xyz", opts).ok());
  auto pc = ReadXyz("0 0 0\n1 1 1\n2 2 2\n", "l.xyz", opts);
  ASSERT_FALSE(pc.ok());
  EXPECT_EQ(pc.status().code(), StatusCode::kLimitExceeded);
  EXPECT_NE(pc.status().message().find("l.xyz: more than 2 points"), std::string::npos) << pc.status().message();
}

TEST(PointCloudFiles, DispatchByExtensionAndGzip) {
  testing::TempDir dir;
  EXPECT_EQ(MeshFormatFromPath("scan.XYZ"), MeshFormat::kXyz);
  EXPECT_EQ(MeshFormatFromPath("scan.pts.gz"), MeshFormat::kXyz);
  EXPECT_STREQ(MeshFormatName(MeshFormat::kXyz), "XYZ");
  const std::string xyz = dir.Write("s.xyz", "0 0 0\n1 0 0\n0 1 0\n");
  auto pc = ReadMeshOrPointCloudFile(xyz);
  ASSERT_TRUE(pc.ok()) << pc.status().ToString();
  EXPECT_EQ(pc->mesh.positions.size(), 3u);
  auto as_mesh = ReadMeshFile(xyz);  // the tokenizer's view: no faces
  ASSERT_FALSE(as_mesh.ok());
  EXPECT_NE(as_mesh.status().message().find("s.xyz: no faces (an XYZ file is a point cloud of 3 points)"),
            std::string::npos)
      << as_mesh.status().message();
  const std::string ply =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
      "property float z\nproperty float nx\nproperty float ny\nproperty float nz\n"
      "element face 1\nproperty list uchar int vertex_indices\nend_header\n"
      "0 0 0 0 0 1\n1 0 0 0 0 1\n0 1 0 0 0 1\n3 0 1 2\n";
  auto mesh = ReadMeshOrPointCloudFile(dir.Write("m.ply", ply));  // a PLY mesh: normals dropped
  ASSERT_TRUE(mesh.ok());
  EXPECT_EQ(mesh->mesh.triangles.size(), 1u);
  EXPECT_TRUE(mesh->normals.empty());
  auto obj = ReadMeshOrPointCloudFile(dir.Write("t.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"));
  ASSERT_TRUE(obj.ok());
  EXPECT_EQ(obj->mesh.triangles.size(), 1u);
  auto missing = ReadMeshOrPointCloudFile(dir.path() + "/none.xyz");
  ASSERT_FALSE(missing.ok());
  EXPECT_NE(missing.status().message().find("none.xyz"), std::string::npos);
#ifdef SILK_HAVE_ZLIB
  auto gz = ReadMeshOrPointCloudFile(dir.Write("s.xyz.gz", testing::Gzip("0 0 0 0 0 1\n1 0 0 0 0 1\n")));
  ASSERT_TRUE(gz.ok()) << gz.status().ToString();
  EXPECT_EQ(gz->normals.size(), 2u);
  const std::string cloud_ply =
      "ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nproperty float y\n"
      "property float z\nend_header\n0 0 0\n1 1 1\n";
  auto plygz = ReadMeshOrPointCloudFile(dir.Write("c.ply.gz", testing::Gzip(cloud_ply)));
  ASSERT_TRUE(plygz.ok()) << plygz.status().ToString();
  EXPECT_EQ(plygz->mesh.positions.size(), 2u);
  EXPECT_TRUE(plygz->normals.empty());
#endif
}

}  // namespace
}  // namespace silk
