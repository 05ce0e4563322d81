// SPDX-License-Identifier: MIT
// Parts keep the order of their component index; each is named part_NNN.
#include "mesh/glb_parts.h"

#include <array>
#include <cmath>
#include <cstdio>
#include <map>

#include "mesh/vertex_normals.h"

namespace silk {

namespace {

// Well-separated hues (golden-angle steps), fixed saturation/value.
std::array<float, 3> PartColor(int part) {
  const double h = std::fmod(part * 0.618033988749895, 1.0) * 6.0;
  const double s = 0.55, v = 0.9, c = v * s, x = c * (1 - std::fabs(std::fmod(h, 2.0) - 1)), m = v - c;
  double r = 0, g = 0, b = 0;
  switch (static_cast<int>(h)) {
    case 0:
      r = c;
      g = x;
      break;
    case 1:
      r = x;
      g = c;
      break;
    case 2:
      g = c;
      b = x;
      break;
    case 3:
      g = x;
      b = c;
      break;
    case 4:
      r = x;
      b = c;
      break;
    default:
      r = c;
      b = x;
      break;
  }
  return {static_cast<float>(r + m), static_cast<float>(g + m), static_cast<float>(b + m)};
}

}  // namespace

std::vector<GlbPart> SplitGlbParts(const IoMesh& mesh, const std::vector<int32_t>& triangle_component, bool colors) {
  std::map<int32_t, std::vector<size_t>> by_part;
  for (size_t f = 0; f < mesh.triangles.size(); ++f)
    by_part[f < triangle_component.size() ? triangle_component[f] : 0].push_back(f);
  std::vector<GlbPart> parts;
  int index = 0;
  for (const auto& [component, faces] : by_part) {
    IoMesh part;
    std::vector<int32_t> remap(mesh.positions.size(), -1);
    for (size_t f : faces) {
      std::array<int32_t, 3> t{};
      for (int k = 0; k < 3; ++k) {
        const int32_t v = mesh.triangles[f][k];
        if (remap[v] < 0) {
          remap[v] = static_cast<int32_t>(part.positions.size());
          part.positions.push_back(mesh.positions[v]);
        }
        t[k] = remap[v];
      }
      part.triangles.push_back(t);
    }
    const auto normals = SmoothVertexNormals(part);
    GlbPart out;
    char name[32];
    std::snprintf(name, sizeof(name), "part_%03d", index);
    out.name = name;
    for (size_t i = 0; i < part.positions.size(); ++i) {
      const auto& p = part.positions[i];
      out.positions.push_back({static_cast<float>(p[0]), static_cast<float>(p[1]), static_cast<float>(p[2])});
      out.normals.push_back(
          {static_cast<float>(normals[i][0]), static_cast<float>(normals[i][1]), static_cast<float>(normals[i][2])});
    }
    for (const auto& t : part.triangles)
      out.triangles.push_back({static_cast<uint32_t>(t[0]), static_cast<uint32_t>(t[1]), static_cast<uint32_t>(t[2])});
    if (colors) out.color = PartColor(index);
    parts.push_back(std::move(out));
    ++index;
    (void)component;
  }
  return parts;
}

}  // namespace silk
