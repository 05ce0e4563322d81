// SPDX-License-Identifier: MIT
// Leader clustering on a hash grid, then face filtering and vertex compaction.
#include "mesh/close_vertex_merge.h"

#include <algorithm>
#include <cmath>
#include <set>
#include <unordered_map>
#include <vector>

namespace silk {

namespace {

using V3 = std::array<double, 3>;

struct CellKey {
  int64_t x, y, z;
  bool operator==(const CellKey& o) const { return x == o.x && y == o.y && z == o.z; }
};
struct CellHash {
  size_t operator()(const CellKey& k) const {
    uint64_t h = static_cast<uint64_t>(k.x) * 0x9E3779B97F4A7C15ull;
    h ^= static_cast<uint64_t>(k.y) * 0xC2B2AE3D27D4EB4Full + (h << 6) + (h >> 2);
    h ^= static_cast<uint64_t>(k.z) * 0x165667B19E3779F9ull + (h << 6) + (h >> 2);
    return static_cast<size_t>(h);
  }
};

double Distance2(const V3& a, const V3& b) {
  const double dx = a[0] - b[0], dy = a[1] - b[1], dz = a[2] - b[2];
  return dx * dx + dy * dy + dz * dz;
}

std::vector<bool> ReferencedVertices(const IoMesh& mesh) {
  std::vector<bool> used(mesh.positions.size(), false);
  for (const auto& t : mesh.triangles)
    for (int32_t v : t) used[static_cast<size_t>(v)] = true;
  return used;
}

// Per-axis min/max of the referenced vertices (zeros when there are none).
void ReferencedBounds(const IoMesh& mesh, const std::vector<bool>& used, V3* lo, V3* hi) {
  *lo = {0, 0, 0};
  *hi = {0, 0, 0};
  bool any = false;
  for (size_t i = 0; i < used.size(); ++i) {
    if (!used[i]) continue;
    for (int a = 0; a < 3; ++a) {
      const double x = mesh.positions[i][a];
      (*lo)[a] = any ? std::min((*lo)[a], x) : x;
      (*hi)[a] = any ? std::max((*hi)[a], x) : x;
    }
    any = true;
  }
}

// Leader of every referenced vertex (itself when it leads; -1 for unreferenced ones).
std::vector<int32_t> Leaders(const IoMesh& mesh, const std::vector<bool>& used, double distance) {
  const size_t n = mesh.positions.size();
  std::vector<int32_t> leader(n, -1);
  V3 lo, hi;
  ReferencedBounds(mesh, used, &lo, &hi);
  std::unordered_map<CellKey, std::vector<int32_t>, CellHash> grid;
  const double d2 = distance * distance;
  for (size_t i = 0; i < n; ++i) {
    if (!used[i]) continue;
    leader[i] = static_cast<int32_t>(i);
    if (!(distance > 0)) continue;
    const V3& p = mesh.positions[i];
    const CellKey c{static_cast<int64_t>(std::floor((p[0] - lo[0]) / distance)),
                    static_cast<int64_t>(std::floor((p[1] - lo[1]) / distance)),
                    static_cast<int64_t>(std::floor((p[2] - lo[2]) / distance))};
    double best = d2;
    for (int64_t dx = -1; dx <= 1; ++dx)
      for (int64_t dy = -1; dy <= 1; ++dy)
        for (int64_t dz = -1; dz <= 1; ++dz) {
          auto it = grid.find({c.x + dx, c.y + dy, c.z + dz});
          if (it == grid.end()) continue;
          for (int32_t l : it->second) {
            const double e = Distance2(p, mesh.positions[static_cast<size_t>(l)]);
            if (e < best) best = e, leader[i] = l;
          }
        }
    if (leader[i] == static_cast<int32_t>(i)) grid[c].push_back(leader[i]);
  }
  return leader;
}

bool ZeroArea(const V3& a, const V3& b, const V3& c) {
  const V3 u{b[0] - a[0], b[1] - a[1], b[2] - a[2]}, v{c[0] - a[0], c[1] - a[1], c[2] - a[2]};
  const V3 x{u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
  return x[0] == 0 && x[1] == 0 && x[2] == 0;
}

}  // namespace

double ReferencedBoundingBoxDiagonal(const IoMesh& mesh) {
  V3 lo, hi;
  ReferencedBounds(mesh, ReferencedVertices(mesh), &lo, &hi);
  return std::sqrt(Distance2(lo, hi));
}

IoMesh MergeCloseVertices(const IoMesh& mesh, double distance, VertexMergeReport* report) {
  const std::vector<bool> used = ReferencedVertices(mesh);
  const std::vector<int32_t> leader = Leaders(mesh, used, distance);
  std::vector<std::array<int32_t, 3>> faces;
  std::set<std::array<int32_t, 3>> seen;
  for (const auto& t : mesh.triangles) {
    const std::array<int32_t, 3> f = {leader[static_cast<size_t>(t[0])], leader[static_cast<size_t>(t[1])],
                                      leader[static_cast<size_t>(t[2])]};
    if (f[0] == f[1] || f[1] == f[2] || f[0] == f[2]) continue;
    if (ZeroArea(mesh.positions[static_cast<size_t>(f[0])], mesh.positions[static_cast<size_t>(f[1])],
                 mesh.positions[static_cast<size_t>(f[2])]))
      continue;
    std::array<int32_t, 3> key = f;
    std::sort(key.begin(), key.end());
    if (!seen.insert(key).second) continue;
    faces.push_back(f);
  }
  IoMesh out;
  std::vector<int32_t> new_index(mesh.positions.size(), -1);
  for (auto& f : faces)
    for (int32_t& v : f) {
      int32_t& ni = new_index[static_cast<size_t>(v)];
      if (ni < 0) {
        ni = static_cast<int32_t>(out.positions.size());
        out.positions.push_back(mesh.positions[static_cast<size_t>(v)]);
      }
      v = ni;
    }
  out.triangles = std::move(faces);
  if (report) {
    report->vertices_before = static_cast<int64_t>(mesh.positions.size());
    report->faces_before = static_cast<int64_t>(mesh.triangles.size());
    report->vertices_after = static_cast<int64_t>(out.positions.size());
    report->faces_after = static_cast<int64_t>(out.triangles.size());
  }
  return out;
}

}  // namespace silk
