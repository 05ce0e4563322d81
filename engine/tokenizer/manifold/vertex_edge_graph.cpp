// SPDX-License-Identifier: MIT
// Edge graph construction and structural summary (token_format.md §3.2); sizes are bounded by the
// 50-face incident-list limit, so linear scans are used throughout.
#include "tokenizer/manifold/vertex_edge_graph.h"

#include <algorithm>

namespace silk {

int32_t VertexEdgeGraph::FaceOf(int32_t a, int32_t b) const {
  const std::pair<int32_t, int32_t> k = a < b ? std::make_pair(a, b) : std::make_pair(b, a);
  for (size_t i = 0; i < keys.size(); ++i)
    if (keys[i] == k) return face[i];
  return -1;
}

VertexEdgeGraph BuildVertexEdgeGraph(const std::vector<std::array<int32_t, 3>>& faces, int32_t v,
                                     const int32_t* face_list, size_t count) {
  VertexEdgeGraph g;
  g.keys.reserve(count);
  g.face.reserve(count);
  for (size_t i = 0; i < count; ++i) {
    const int32_t f = face_list[i];
    const auto& t = faces[static_cast<size_t>(f)];
    int32_t o[2];
    int32_t n = 0;
    for (int32_t c : t)
      if (c != v && n < 2) o[n++] = c;
    const std::pair<int32_t, int32_t> k = o[0] < o[1] ? std::make_pair(o[0], o[1]) : std::make_pair(o[1], o[0]);
    auto it = std::find(g.keys.begin(), g.keys.end(), k);
    if (it != g.keys.end()) {
      g.face[static_cast<size_t>(it - g.keys.begin())] = f;
    } else {
      g.keys.push_back(k);
      g.face.push_back(f);
    }
  }
  return g;
}

EdgeGraphShape InspectEdgeGraph(const std::vector<std::pair<int32_t, int32_t>>& keys) {
  EdgeGraphShape s;
  std::vector<int32_t> names, degree, parent;
  auto local = [&](int32_t name) {
    for (size_t i = 0; i < names.size(); ++i)
      if (names[i] == name) return static_cast<int32_t>(i);
    names.push_back(name);
    degree.push_back(0);
    parent.push_back(static_cast<int32_t>(parent.size()));
    return static_cast<int32_t>(names.size()) - 1;
  };
  auto find = [&](int32_t a) {
    while (parent[static_cast<size_t>(a)] != a)
      a = parent[static_cast<size_t>(a)] = parent[static_cast<size_t>(parent[static_cast<size_t>(a)])];
    return a;
  };
  for (const auto& k : keys) {
    const int32_t a = local(k.first), b = local(k.second);
    const int32_t da = ++degree[static_cast<size_t>(a)];
    const int32_t db = ++degree[static_cast<size_t>(b)];
    if (da > 2 || db > 2) s.max_degree_le2 = false;
    const int32_t ra = find(a), rb = find(b);
    if (ra != rb) parent[static_cast<size_t>(ra)] = rb;
  }
  s.nodes = static_cast<int32_t>(names.size());
  std::vector<int32_t> node_count(names.size(), 0), edge_count(names.size(), 0);
  for (size_t i = 0; i < names.size(); ++i) {
    if (find(static_cast<int32_t>(i)) == static_cast<int32_t>(i)) ++s.components;
    ++node_count[static_cast<size_t>(find(static_cast<int32_t>(i)))];
  }
  for (const auto& k : keys) ++edge_count[static_cast<size_t>(find(local(k.first)))];
  for (size_t i = 0; i < names.size(); ++i)
    if (edge_count[i] > node_count[i]) s.component_with_extra_edge = true;
  return s;
}

}  // namespace silk
