// SPDX-License-Identifier: MIT
// GLB output read back by the project's own glTF reader, plus the container layout rules
// (4-byte chunks, declared length).
#include <gtest/gtest.h>

#include <cstring>

#include "io/gltf/glb_writer.h"
#include "io/mesh_reader.h"

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

}  // namespace
}  // namespace silk
