// SPDX-License-Identifier: MIT
// Edge incidence by sorting directed edges once (no hash maps, deterministic).
#include "mesh/mesh_checks.h"

#include <algorithm>
#include <array>
#include <vector>

#include "mesh/vertex_fans.h"

namespace silk {

MeshVerdicts CheckMesh(const IoMesh& mesh) {
  return CheckFaces(mesh.triangles, static_cast<int32_t>(mesh.positions.size()));
}

MeshVerdicts CheckFaces(const std::vector<std::array<int32_t, 3>>& faces, int32_t num_vertices) {
  MeshVerdicts v;
  std::vector<std::array<int32_t, 2>> directed;
  directed.reserve(faces.size() * 3);
  for (const auto& t : faces)
    for (int k = 0; k < 3; ++k) directed.push_back({t[k], t[(k + 1) % 3]});
  std::vector<std::array<int32_t, 2>> sorted_directed = directed;
  std::sort(sorted_directed.begin(), sorted_directed.end());
  for (size_t i = 1; i < sorted_directed.size(); ++i)
    if (sorted_directed[i] == sorted_directed[i - 1]) v.consistently_oriented = false;
  std::vector<std::array<int32_t, 2>> undirected = directed;
  for (auto& e : undirected)
    if (e[0] > e[1]) std::swap(e[0], e[1]);
  std::sort(undirected.begin(), undirected.end());
  for (size_t i = 0; i < undirected.size();) {
    size_t j = i;
    while (j < undirected.size() && undirected[j] == undirected[i]) ++j;
    const size_t n = j - i;
    if (n == 1) ++v.boundary_edges;
    if (n >= 3) ++v.nonmanifold_edges;
    i = j;
  }
  v.edge_manifold = v.nonmanifold_edges == 0;
  v.nonmanifold_vertices = ComputeVertexFans(faces, num_vertices).nonmanifold_vertices;
  v.vertex_manifold = v.nonmanifold_vertices == 0;
  v.watertight = !faces.empty() && v.boundary_edges == 0 && v.nonmanifold_edges == 0;
  return v;
}

}  // namespace silk
