// SPDX-License-Identifier: MIT
// glTF reader: embedded-buffer .gltf and in-memory GLB built here, node transforms, strips,
// non-indexed primitives, and the validation errors (cycles, bounds, missing buffers).
#include "io/gltf/gltf_reader.h"

#include <gtest/gtest.h>

#include "io/mesh_reader.h"
#include "io/io_test_util.h"

namespace silk {
namespace {

std::string Base64(const std::string& in) {
  static const char* tbl = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  size_t i = 0;
  for (; i + 2 < in.size(); i += 3) {
    uint32_t v = uint32_t(uint8_t(in[i])) << 16 | uint32_t(uint8_t(in[i + 1])) << 8 | uint8_t(in[i + 2]);
    for (int k = 3; k >= 0; --k) out += tbl[(v >> (6 * k)) & 63];
  }
  if (i + 1 == in.size()) {
    uint32_t v = uint32_t(uint8_t(in[i])) << 16;
    out += tbl[(v >> 18) & 63];
    out += tbl[(v >> 12) & 63];
    out += "==";
  } else if (i + 2 == in.size()) {
    uint32_t v = uint32_t(uint8_t(in[i])) << 16 | uint32_t(uint8_t(in[i + 1])) << 8;
    out += tbl[(v >> 18) & 63];
    out += tbl[(v >> 12) & 63];
    out += tbl[(v >> 6) & 63];
    out += '=';
  }
  return out;
}

// Buffer: 4 positions (48 bytes) then 6 uint16 indices (12 bytes).
std::string GeometryBuffer(uint16_t last_index = 3) {
  std::string b;
  const float p[12] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
  for (float v : p) testing::AppendLE(&b, v);
  for (uint16_t i : {uint16_t{0}, uint16_t{1}, uint16_t{2}, uint16_t{0}, uint16_t{2}, last_index})
    testing::AppendLE(&b, i);
  return b;
}

// `buffer_json` is the buffers[0] object; `nodes_json`/`scenes_json` describe the graph.
std::string GltfJson(const std::string& buffer_json, const std::string& nodes_json,
                     const std::string& scenes_json = R"("scene": 0, "scenes": [{"nodes": [0]}],)",
                     const std::string& mode = "4") {
  return std::string(R"({"asset": {"version": "2.0"}, )") + scenes_json + R"( "nodes": )" + nodes_json + R"(,
    "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1, "mode": )" +
         mode + R"(},
                               {"attributes": {"POSITION": 0}}]}],
    "accessors": [
      {"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3"},
      {"bufferView": 1, "componentType": 5123, "count": 6, "type": "SCALAR"}],
    "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 48},
                    {"buffer": 0, "byteOffset": 48, "byteLength": 12}],
    "buffers": [)" +
         buffer_json + "]}";
}

std::string EmbeddedBuffer(const std::string& bytes) {
  return R"({"byteLength": )" + std::to_string(bytes.size()) + R"(, "uri": "data:application/octet-stream;base64,)" +
         Base64(bytes) + R"("})";
}

std::string Glb(std::string json, const std::string& bin) {
  while (json.size() % 4) json += ' ';
  std::string b = bin;
  while (b.size() % 4) b.push_back('\0');
  std::string out = "glTF";
  testing::AppendLE(&out, uint32_t{2});
  testing::AppendLE(&out, static_cast<uint32_t>(12 + 8 + json.size() + 8 + b.size()));
  testing::AppendLE(&out, static_cast<uint32_t>(json.size()));
  testing::AppendLE(&out, uint32_t{0x4E4F534A});
  out += json;
  testing::AppendLE(&out, static_cast<uint32_t>(b.size()));
  testing::AppendLE(&out, uint32_t{0x004E4942});
  out += b;
  return out;
}

const char* kTransformNodes =
    R"([{"translation": [10, 0, 0], "scale": [2, 2, 2], "children": [1]},
        {"mesh": 0, "matrix": [1,0,0,0, 0,1,0,0, 0,0,1,0, 0,5,0,1]}])";

TEST(GltfReader, TransformsAndIndexedTriangles) {
  std::string json = GltfJson(EmbeddedBuffer(GeometryBuffer()), kTransformNodes);
  // Drop the non-indexed primitive (4 corners is not a valid TRIANGLES count).
  const std::string second = R"(,
                               {"attributes": {"POSITION": 0}})";
  json.erase(json.find(second), second.size());
  auto m = ReadGltf(json, false, "t.gltf", "", true);
  ASSERT_TRUE(m.ok()) << m.status().ToString();
  ASSERT_EQ(m->positions.size(), 4u);
  ASSERT_EQ(m->triangles.size(), 2u);
  EXPECT_EQ(m->triangles[1], (std::array<int32_t, 3>{0, 2, 3}));
  // world = T(10,0,0) * S(2) * T(0,5,0): (1,0,0) -> (2*1+10, 2*5, 0)
  EXPECT_EQ(m->positions[1], (std::array<double, 3>{12, 10, 0}));
  EXPECT_EQ(m->positions[3], (std::array<double, 3>{10, 10, 2}));
}

TEST(GltfReader, NonIndexedPrimitiveWithFourCornersIsAnError) {
  std::string json = GltfJson(EmbeddedBuffer(GeometryBuffer()), kTransformNodes);
  auto m = ReadGltf(json, false, "t.gltf", "", true);
  ASSERT_FALSE(m.ok());
  EXPECT_NE(m.status().message().find("t.gltf: mesh 0 primitive 1: 4 corners is not a multiple of 3"),
            std::string::npos)
      << m.status().message();
}

TEST(GltfReader, TriangleStripAndNonIndexedFan) {
  std::string json =
      GltfJson(EmbeddedBuffer(GeometryBuffer()), R"([{"mesh": 0}])", R"("scene": 0, "scenes": [{"nodes": [0]}],)", "5");
  const std::string second = R"({"attributes": {"POSITION": 0}})";
  json.replace(json.find(second), second.size(), R"({"attributes": {"POSITION": 0}, "mode": 6})");
  auto m = ReadGltf(json, false, "s.gltf", "", true);
  ASSERT_TRUE(m.ok()) << m.status().ToString();
  ASSERT_EQ(m->positions.size(), 8u);
  // strip over corners 0 1 2 0 2 3: 4 triangles, odd ones with the first two swapped.
  ASSERT_EQ(m->triangles.size(), 4u + 2u);
  EXPECT_EQ(m->triangles[0], (std::array<int32_t, 3>{0, 1, 2}));
  EXPECT_EQ(m->triangles[1], (std::array<int32_t, 3>{2, 1, 0}));
  // fan over 4 implicit corners of the second copy (base 4): (1,2,0) (2,3,0)
  EXPECT_EQ(m->triangles[4], (std::array<int32_t, 3>{5, 6, 4}));
  EXPECT_EQ(m->triangles[5], (std::array<int32_t, 3>{6, 7, 4}));
}

TEST(GltfReader, NegativeScaleFlipsWinding) {
  std::string json = GltfJson(EmbeddedBuffer(GeometryBuffer()), R"([{"mesh": 0, "scale": [-1, 1, 1]}])");
  const std::string second = R"(,
                               {"attributes": {"POSITION": 0}})";
  json.erase(json.find(second), second.size());
  auto m = ReadGltf(json, false, "n.gltf", "", true);
  ASSERT_TRUE(m.ok()) << m.status().ToString();
  EXPECT_EQ(m->triangles[0], (std::array<int32_t, 3>{0, 2, 1}));
  EXPECT_EQ(m->positions[1], (std::array<double, 3>{-1, 0, 0}));
}

TEST(GltfReader, GlbInMemoryAndThroughFile) {
  std::string json = GltfJson(R"({"byteLength": 60})", R"([{"mesh": 0}])");
  const std::string second = R"(,
                               {"attributes": {"POSITION": 0}})";
  json.erase(json.find(second), second.size());
  std::string glb = Glb(json, GeometryBuffer());
  auto m = ReadMeshFromMemory(reinterpret_cast<const uint8_t*>(glb.data()), glb.size(), MeshFormat::kGlb, "m.glb");
  ASSERT_TRUE(m.ok()) << m.status().ToString();
  EXPECT_EQ(m->triangles.size(), 2u);
  EXPECT_EQ(m->positions[3], (std::array<double, 3>{0, 0, 1}));

  testing::TempDir dir;
  auto f = ReadMeshFile(dir.Write("m.glb", glb));
  ASSERT_TRUE(f.ok()) << f.status().ToString();
  EXPECT_EQ(f->triangles.size(), 2u);
}

TEST(GltfReader, ExternalBufferFileAndMissingBuffer) {
  std::string json = GltfJson(R"({"byteLength": 60, "uri": "geo%20data.bin"})", R"([{"mesh": 0}])");
  const std::string second = R"(,
                               {"attributes": {"POSITION": 0}})";
  json.erase(json.find(second), second.size());
  testing::TempDir dir;
  std::string path = dir.Write("ext.gltf", json);
  auto missing = ReadMeshFile(path);
  ASSERT_FALSE(missing.ok());
  EXPECT_NE(missing.status().message().find("ext.gltf: buffer 0: external file 'geo%20data.bin' not found"),
            std::string::npos)
      << missing.status().message();
  dir.Write("geo data.bin", GeometryBuffer());
  auto m = ReadMeshFile(path);
  ASSERT_TRUE(m.ok()) << m.status().ToString();
  EXPECT_EQ(m->triangles.size(), 2u);
  // From memory, external files are never opened.
  auto mem =
      ReadMeshFromMemory(reinterpret_cast<const uint8_t*>(json.data()), json.size(), MeshFormat::kGltf, "mem.gltf");
  ASSERT_FALSE(mem.ok());
  EXPECT_NE(mem.status().message().find("cannot be loaded (mesh read from memory)"), std::string::npos);
}

TEST(GltfReader, ValidationErrors) {
  const std::string emb = EmbeddedBuffer(GeometryBuffer());
  struct Case {
    std::string json, expect;
  } cases[] = {
      {GltfJson(EmbeddedBuffer(GeometryBuffer(9)), R"([{"mesh": 0}])"),
       "v.gltf: mesh 0 primitive 0: index 9 (at 5) out of range (4 vertices)"},
      {GltfJson(emb, R"([{"children": [1]}, {"children": [0], "mesh": 0}])"),
       "v.gltf: node graph is not a tree: node 0 is reached twice"},
      {GltfJson(emb, R"([{"mesh": 0, "children": [7]}])"), "v.gltf: node 0 refers to node 7, which does not exist"},
      {GltfJson(emb, R"([{"mesh": 3}])"), "v.gltf: node 0 refers to mesh 3, which does not exist"},
      {GltfJson(emb, R"([{"mesh": 0}])", R"("scene": 2, "scenes": [{"nodes": [0]}],)"), "v.gltf: "},
      {std::string(200, '[') + std::string(200, ']'), "v.gltf: glTF JSON nests deeper than 64 levels"},
      {"{\"asset\": ", "v.gltf: glTF JSON is not valid JSON"},
      {R"({"asset": {"version": "2.0"}, "scenes": [{"nodes": []}], "scene": 0})", "v.gltf: no faces"},
  };
  for (const auto& c : cases) {
    auto m = ReadGltf(c.json, false, "v.gltf", "", true);
    ASSERT_FALSE(m.ok()) << c.json.substr(0, 200);
    EXPECT_NE(m.status().message().find(c.expect), std::string::npos)
        << "message: " << m.status().message() << "\nexpected: " << c.expect;
  }
}

TEST(GltfReader, AccessorPastBufferEnd) {
  std::string json = GltfJson(EmbeddedBuffer(GeometryBuffer()), R"([{"mesh": 0}])");
  json.replace(json.find(R"("count": 4)"), 10, R"("count": 40)");
  auto m = ReadGltf(json, false, "b.gltf", "", true);
  ASSERT_FALSE(m.ok());
  EXPECT_NE(m.status().message().find("b.gltf: "), std::string::npos) << m.status().message();
}

TEST(GltfReader, GlbWithoutMagic) {
  auto m = ReadGltf("v 0 0 0\n", true, "x.glb", "", true);
  ASSERT_FALSE(m.ok());
  EXPECT_EQ(m.status().message(), "x.glb: not a GLB file (no 'glTF' magic)");
}

}  // namespace
}  // namespace silk
