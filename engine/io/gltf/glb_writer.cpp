// SPDX-License-Identifier: MIT
// GLB layout: 12-byte header, JSON chunk (space-padded to 4), BIN chunk (zero-padded); one
// buffer whose views are 4-byte aligned. Accessor min/max for POSITION as the spec requires.
#include "io/gltf/glb_writer.h"

#include <algorithm>
#include <cstring>
#include <limits>

#include <nlohmann/json.hpp>

#include "io/files/atomic_file.h"

namespace silk {

namespace {

using Json = nlohmann::ordered_json;

constexpr int kArrayBuffer = 34962, kElementArrayBuffer = 34963;
constexpr int kFloat = 5126, kUnsignedInt = 5125;

void Pad(std::string* s, char fill) {
  while (s->size() % 4) s->push_back(fill);
}

void PutU32(std::string* s, uint32_t v) {
  for (int i = 0; i < 4; ++i) s->push_back(static_cast<char>((v >> (8 * i)) & 0xFF));
}

// Appends raw bytes as a new buffer view + accessor; returns the accessor index.
int AddAccessor(Json* doc, std::string* bin, const void* data, size_t bytes, int target, int component_type,
                size_t count, const char* type, const Json& min = nullptr, const Json& max = nullptr) {
  Pad(bin, '\0');
  const size_t offset = bin->size();
  bin->append(static_cast<const char*>(data), bytes);
  Json view = {{"buffer", 0}, {"byteOffset", offset}, {"byteLength", bytes}, {"target", target}};
  (*doc)["bufferViews"].push_back(view);
  Json acc = {{"bufferView", (*doc)["bufferViews"].size() - 1},
              {"componentType", component_type},
              {"count", count},
              {"type", type}};
  if (!min.is_null()) acc["min"] = min;
  if (!max.is_null()) acc["max"] = max;
  (*doc)["accessors"].push_back(acc);
  return static_cast<int>((*doc)["accessors"].size() - 1);
}

}  // namespace

StatusOr<std::string> FormatGlb(const std::vector<GlbPart>& parts, const std::string& generator) {
  Json doc;
  doc["asset"] = {{"version", "2.0"}, {"generator", generator}};
  doc["scene"] = 0;
  doc["scenes"] = Json::array({Json{{"nodes", Json::array()}}});
  doc["nodes"] = Json::array();
  doc["meshes"] = Json::array();
  doc["accessors"] = Json::array();
  doc["bufferViews"] = Json::array();
  std::string bin;
  for (const GlbPart& part : parts) {
    const size_t nv = part.positions.size();
    if (nv == 0 || part.triangles.empty()) continue;
    if (!part.normals.empty() && part.normals.size() != nv)
      return InvalidArgument("glb: part '" + part.name + "' has " + std::to_string(part.normals.size()) +
                             " normals for " + std::to_string(nv) + " positions");
    for (const auto& t : part.triangles)
      for (uint32_t i : t)
        if (i >= nv) return InvalidArgument("glb: part '" + part.name + "' has an index out of range");
    std::array<float, 3> lo, hi;
    lo.fill(std::numeric_limits<float>::max());
    hi.fill(std::numeric_limits<float>::lowest());
    for (const auto& p : part.positions)
      for (int d = 0; d < 3; ++d) {
        lo[d] = std::min(lo[d], p[d]);
        hi[d] = std::max(hi[d], p[d]);
      }
    Json attributes;
    attributes["POSITION"] =
        AddAccessor(&doc, &bin, part.positions.data(), nv * 12, kArrayBuffer, kFloat, nv, "VEC3", Json(lo), Json(hi));
    if (!part.normals.empty())
      attributes["NORMAL"] = AddAccessor(&doc, &bin, part.normals.data(), nv * 12, kArrayBuffer, kFloat, nv, "VEC3");
    if (part.color) {
      std::vector<std::array<float, 3>> colors(nv, *part.color);
      attributes["COLOR_0"] = AddAccessor(&doc, &bin, colors.data(), nv * 12, kArrayBuffer, kFloat, nv, "VEC3");
    }
    const size_t ni = part.triangles.size() * 3;
    const int indices =
        AddAccessor(&doc, &bin, part.triangles.data(), ni * 4, kElementArrayBuffer, kUnsignedInt, ni, "SCALAR");
    Json prim = {{"attributes", attributes}, {"indices", indices}, {"mode", 4}};
    doc["meshes"].push_back({{"name", part.name}, {"primitives", Json::array({prim})}});
    doc["nodes"].push_back({{"name", part.name}, {"mesh", doc["meshes"].size() - 1}});
    doc["scenes"][0]["nodes"].push_back(doc["nodes"].size() - 1);
  }
  Pad(&bin, '\0');
  if (!bin.empty()) doc["buffers"] = Json::array({Json{{"byteLength", bin.size()}}});
  if (doc["accessors"].empty()) {
    doc.erase("accessors");
    doc.erase("bufferViews");
    doc.erase("meshes");
    doc.erase("nodes");
    doc["scenes"] = Json::array({Json::object()});  // glTF arrays must not be empty
  }
  std::string json = doc.dump();
  Pad(&json, ' ');
  const uint64_t total = 12 + 8 + json.size() + (bin.empty() ? 0 : 8 + bin.size());
  if (total > std::numeric_limits<uint32_t>::max()) return LimitExceeded("glb: output larger than 4 GiB");
  std::string out;
  out.reserve(static_cast<size_t>(total));
  out.append("glTF", 4);
  PutU32(&out, 2);
  PutU32(&out, static_cast<uint32_t>(total));
  PutU32(&out, static_cast<uint32_t>(json.size()));
  out.append("JSON", 4);
  out += json;
  if (!bin.empty()) {
    PutU32(&out, static_cast<uint32_t>(bin.size()));
    out.append("BIN\0", 4);
    out += bin;
  }
  return out;
}

Status WriteGlbFile(const std::string& path, const std::vector<GlbPart>& parts, const std::string& generator) {
  SILK_ASSIGN_OR_RETURN(std::string bytes, FormatGlb(parts, generator));
  return WriteFileAtomically(path, bytes);
}

}  // namespace silk
