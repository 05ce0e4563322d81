// Parts for GLB: triangles grouped by component, vertices re-indexed per part, normals
// computed per part (mesh/vertex_normals) so parts do not smooth across each other.
#include "output_writer.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <map>

#include "io/glb_writer.h"
#include "io/obj_writer.h"
#include "io/ply_writer.h"
#include "mesh/vertex_normals.h"

namespace silkgen {

namespace {

std::string Lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

bool EndsWith(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

// Well-separated hues (golden-angle steps), fixed saturation/value.
std::array<float, 3> PartColor(int part) {
  const double h = std::fmod(part * 0.618033988749895, 1.0) * 6.0;
  const double s = 0.55, v = 0.9, c = v * s, x = c * (1 - std::fabs(std::fmod(h, 2.0) - 1)), m = v - c;
  double r = 0, g = 0, b = 0;
  switch (static_cast<int>(h)) {
    case 0: r = c; g = x; break;
    case 1: r = x; g = c; break;
    case 2: g = c; b = x; break;
    case 3: g = x; b = c; break;
    case 4: r = x; b = c; break;
    default: r = c; b = x; break;
  }
  return {static_cast<float>(r + m), static_cast<float>(g + m), static_cast<float>(b + m)};
}

std::vector<silk::GlbPart> MakeParts(const silk::GeneratedMesh& g, bool colors) {
  std::map<int32_t, std::vector<size_t>> by_part;
  for (size_t f = 0; f < g.mesh.triangles.size(); ++f)
    by_part[f < g.triangle_component.size() ? g.triangle_component[f] : 0].push_back(f);
  std::vector<silk::GlbPart> parts;
  int index = 0;
  for (const auto& [component, faces] : by_part) {
    silk::RawMesh part;
    std::vector<int32_t> remap(g.mesh.positions.size(), -1);
    for (size_t f : faces) {
      std::array<int32_t, 3> t{};
      for (int k = 0; k < 3; ++k) {
        const int32_t v = g.mesh.triangles[f][k];
        if (remap[v] < 0) {
          remap[v] = static_cast<int32_t>(part.positions.size());
          part.positions.push_back(g.mesh.positions[v]);
        }
        t[k] = remap[v];
      }
      part.triangles.push_back(t);
    }
    const auto normals = silk::SmoothVertexNormals(part);
    silk::GlbPart out;
    char name[32];
    std::snprintf(name, sizeof(name), "part_%03d", index);
    out.name = name;
    for (size_t i = 0; i < part.positions.size(); ++i) {
      const auto& p = part.positions[i];
      out.positions.push_back({static_cast<float>(p[0]), static_cast<float>(p[1]), static_cast<float>(p[2])});
      out.normals.push_back({static_cast<float>(normals[i][0]), static_cast<float>(normals[i][1]),
                             static_cast<float>(normals[i][2])});
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

}  // namespace

std::string CheckOutputPath(const std::string& path) {
  const std::string p = Lower(path);
  if (EndsWith(p, ".glb") || EndsWith(p, ".obj") || EndsWith(p, ".ply")) return "";
  return path + ": unknown output format (use .glb, .obj or .ply)";
}

silk::Status WriteGeneratedMesh(const std::string& path, const silk::GeneratedMesh& mesh, bool part_colors) {
  const std::string p = Lower(path);
  if (EndsWith(p, ".glb")) return silk::WriteGlbFile(path, MakeParts(mesh, part_colors), "silkgen " SILK_VERSION_STRING);
  if (EndsWith(p, ".obj")) return silk::WriteObjFile(path, mesh.mesh);
  if (EndsWith(p, ".ply")) return silk::WritePlyFile(path, mesh.mesh);
  return silk::InvalidArgument(CheckOutputPath(path));
}

}  // namespace silkgen
