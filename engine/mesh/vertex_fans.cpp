// SPDX-License-Identifier: MIT
// Fans by a per-vertex union-find over its incident faces, joined through the other corner they
// share; sorting (other corner, face) pairs keeps it deterministic and free of hash maps.
#include "mesh/vertex_fans.h"

#include <algorithm>
#include <numeric>

namespace silk {
namespace {

int32_t Find(std::vector<int32_t>& parent, int32_t x) {
  while (parent[x] != x) {
    parent[x] = parent[parent[x]];
    x = parent[x];
  }
  return x;
}

}  // namespace

VertexFans ComputeVertexFans(const std::vector<std::array<int32_t, 3>>& faces, int32_t num_vertices) {
  VertexFans out;
  out.corner_fan.assign(faces.size() * 3, 0);
  out.fans_per_vertex.assign(static_cast<size_t>(std::max(num_vertices, 0)), 0);
  // Corners grouped by vertex (CSR), in face order.
  std::vector<int32_t> start(static_cast<size_t>(num_vertices) + 1, 0);
  for (const auto& f : faces)
    for (int32_t v : f)
      if (v >= 0 && v < num_vertices) ++start[v + 1];
  std::partial_sum(start.begin(), start.end(), start.begin());
  std::vector<int32_t> corners(static_cast<size_t>(start.back()));
  std::vector<int32_t> fill(start.begin(), start.end() - 1);
  for (size_t fi = 0; fi < faces.size(); ++fi)
    for (int k = 0; k < 3; ++k) {
      const int32_t v = faces[fi][k];
      if (v >= 0 && v < num_vertices) corners[fill[v]++] = static_cast<int32_t>(fi * 3 + k);
    }
  std::vector<int32_t> parent, root_fan;
  std::vector<std::array<int32_t, 2>> others;  // (other corner's vertex, local face index)
  for (int32_t v = 0; v < num_vertices; ++v) {
    const int32_t b = start[v], n = start[v + 1] - b;
    if (n == 0) continue;
    parent.resize(n);
    std::iota(parent.begin(), parent.end(), 0);
    others.clear();
    for (int32_t i = 0; i < n; ++i) {
      const int32_t c = corners[b + i], fi = c / 3, k = c % 3;
      others.push_back({faces[fi][(k + 1) % 3], i});
      others.push_back({faces[fi][(k + 2) % 3], i});
    }
    std::sort(others.begin(), others.end());
    for (size_t j = 1; j < others.size(); ++j)
      if (others[j][0] == others[j - 1][0]) parent[Find(parent, others[j][1])] = Find(parent, others[j - 1][1]);
    root_fan.assign(n, -1);
    int32_t fans = 0;
    for (int32_t i = 0; i < n; ++i) {
      const int32_t r = Find(parent, i);
      if (root_fan[r] < 0) root_fan[r] = fans++;
      out.corner_fan[corners[b + i]] = root_fan[r];
    }
    out.fans_per_vertex[v] = fans;
    if (fans > 1) ++out.nonmanifold_vertices;
  }
  return out;
}

int32_t SplitNonManifoldFans(std::vector<std::array<int32_t, 3>>* faces, int32_t num_vertices,
                             std::vector<int32_t>* copy_of) {
  const VertexFans vf = ComputeVertexFans(*faces, num_vertices);
  if (vf.nonmanifold_vertices == 0) return 0;
  // First copy index of each split vertex: fans 1.. of v become first_copy[v] + fan - 1.
  std::vector<int32_t> first_copy(static_cast<size_t>(num_vertices), -1);
  int32_t next = num_vertices, split = 0;
  for (int32_t v = 0; v < num_vertices; ++v) {
    if (vf.fans_per_vertex[v] < 2) continue;
    first_copy[v] = next;
    for (int32_t k = 1; k < vf.fans_per_vertex[v]; ++k) copy_of->push_back(v);
    next += vf.fans_per_vertex[v] - 1;
    ++split;
  }
  for (size_t fi = 0; fi < faces->size(); ++fi)
    for (int k = 0; k < 3; ++k) {
      int32_t& v = (*faces)[fi][k];
      const int32_t fan = vf.corner_fan[fi * 3 + k];
      if (v >= 0 && v < num_vertices && fan > 0) v = first_copy[v] + fan - 1;
    }
  return split;
}

}  // namespace silk
