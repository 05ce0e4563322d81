// SPDX-License-Identifier: MIT
// Extension and magic-byte detection of mesh formats, kept apart from the readers so the
// dispatcher and the tools agree on one mapping.
#include "io/mesh_format.h"

#include <algorithm>
#include <cctype>
#include <cstring>

namespace silk {

const char* MeshFormatName(MeshFormat f) {
  switch (f) {
    case MeshFormat::kObj:
      return "OBJ";
    case MeshFormat::kPly:
      return "PLY";
    case MeshFormat::kStl:
      return "STL";
    case MeshFormat::kOff:
      return "OFF";
    case MeshFormat::kGltf:
      return "glTF";
    case MeshFormat::kGlb:
      return "GLB";
    case MeshFormat::kPmd:
      return "PMD";
    case MeshFormat::kXyz:
      return "XYZ";
  }
  return "unknown";
}

namespace {
std::string Lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}
bool EndsWith(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}
}  // namespace

bool HasGzipSuffix(const std::string& path) { return EndsWith(Lower(path), ".gz"); }

std::optional<MeshFormat> MeshFormatFromPath(const std::string& path) {
  std::string p = Lower(path);
  if (EndsWith(p, ".gz")) p.resize(p.size() - 3);
  if (EndsWith(p, ".obj")) return MeshFormat::kObj;
  if (EndsWith(p, ".ply")) return MeshFormat::kPly;
  if (EndsWith(p, ".stl")) return MeshFormat::kStl;
  if (EndsWith(p, ".off")) return MeshFormat::kOff;
  if (EndsWith(p, ".gltf")) return MeshFormat::kGltf;
  if (EndsWith(p, ".glb")) return MeshFormat::kGlb;
  if (EndsWith(p, ".pmd")) return MeshFormat::kPmd;
  if (EndsWith(p, ".xyz") || EndsWith(p, ".pts")) return MeshFormat::kXyz;
  return std::nullopt;
}

std::optional<MeshFormat> SniffMeshFormat(const uint8_t* data, size_t size) {
  auto starts = [&](const char* magic) {
    size_t n = std::strlen(magic);
    return size >= n && std::memcmp(data, magic, n) == 0;
  };
  if (starts("glTF")) return MeshFormat::kGlb;
  if (starts("PSMD")) return MeshFormat::kPmd;
  if (starts("ply\n") || starts("ply\r\n")) return MeshFormat::kPly;
  if (starts("OFF") || starts("COFF") || starts("NOFF") || starts("CNOFF") || starts("STOFF")) return MeshFormat::kOff;
  if (starts("solid")) return MeshFormat::kStl;
  size_t i = 0;
  while (i < size && std::isspace(data[i])) ++i;
  if (i < size && data[i] == '{') return MeshFormat::kGltf;
  return std::nullopt;
}

}  // namespace silk
