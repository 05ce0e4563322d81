// GLB output read back by the project's own glTF reader, plus the container layout rules
// (4-byte chunks, declared length); and point-cloud PLY reading with normals.
#include <gtest/gtest.h>

#include <cstring>

#include "io/gltf/glb_writer.h"
#include "io/mesh_reader.h"
#include "io/ply/ply_reader.h"

namespace silk {
namespace {

GlbPart Quad(const std::string& name, float x) {
  GlbPart p;
  p.name = name;
  p.positions = {{x, 0, 0}, {x + 1, 0, 0}, {x + 1, 1, 0}, {x, 1, 0}};
  p.normals = {{0, 0, 1}, {0, 0, 1}, {0, 0, 1}, {0, 0, 1}};
  p.triangles = {{0, 1, 2}, {0, 2, 3}};
  return p;
}

uint32_t U32(const std::string& s, size_t at) {
  uint32_t v;
  std::memcpy(&v, s.data() + at, 4);
  return v;
}

TEST(GlbWriter, ReadsBackAsTwoPartsWithNamesAndColors) {
  std::vector<GlbPart> parts = {Quad("part_000", 0), Quad("part_001", 5)};
  parts[1].color = std::array<float, 3>{1, 0, 0};
  auto bytes = FormatGlb(parts);
  ASSERT_TRUE(bytes.ok());
  const std::string& b = *bytes;
  EXPECT_EQ(b.substr(0, 4), "glTF");
  EXPECT_EQ(U32(b, 8), b.size());
  EXPECT_EQ(U32(b, 12) % 4, 0u);
  EXPECT_NE(b.find("\"part_001\""), std::string::npos);
  EXPECT_NE(b.find("COLOR_0"), std::string::npos);
  EXPECT_NE(b.find("NORMAL"), std::string::npos);
  auto mesh = ReadMeshFromMemory(reinterpret_cast<const uint8_t*>(b.data()), b.size(), MeshFormat::kGlb, "t.glb");
  ASSERT_TRUE(mesh.ok()) << mesh.status().ToString();
  EXPECT_EQ(mesh->positions.size(), 8u);
  EXPECT_EQ(mesh->triangles.size(), 4u);
  EXPECT_EQ(mesh->positions[4][0], 5.0);
}

TEST(GlbWriter, EmptyAndInvalid) {
  auto empty = FormatGlb({});
  ASSERT_TRUE(empty.ok());
  EXPECT_EQ(U32(*empty, 8), empty->size());
  GlbPart bad = Quad("x", 0);
  bad.triangles.push_back({0, 1, 9});
  EXPECT_FALSE(FormatGlb({bad}).ok());
  GlbPart few = Quad("y", 0);
  few.normals.pop_back();
  EXPECT_FALSE(FormatGlb({few}).ok());
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
      "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\nend_header\n1 1 1\n";
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
