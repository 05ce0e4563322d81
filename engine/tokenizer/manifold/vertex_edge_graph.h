// SPDX-License-Identifier: MIT
// The edge graph G_v of a vertex (token_format.md §3.2): one keyed edge per incident face, in list
// order, plus a cheap structural summary used to skip the order emulation for plain fans.
#pragma once
#include <array>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

namespace silk {

struct VertexEdgeGraph {
  // Edge keys (min, max) in insertion order and the face labelling each (dict semantics:
  // a repeated key keeps its position, the later face overwrites the label).
  std::vector<std::pair<int32_t, int32_t>> keys;
  std::vector<int32_t> face;
  // Face of edge {a, b}, or -1.
  int32_t FaceOf(int32_t a, int32_t b) const;
};

VertexEdgeGraph BuildVertexEdgeGraph(const std::vector<std::array<int32_t, 3>>& faces, int32_t v,
                                     const int32_t* face_list, size_t count);

struct EdgeGraphShape {
  int32_t nodes = 0;
  int32_t components = 0;
  bool max_degree_le2 = true;              // with one component: a simple path or cycle
  bool component_with_extra_edge = false;  // some component has |edges| > |nodes|
};

EdgeGraphShape InspectEdgeGraph(const std::vector<std::pair<int32_t, int32_t>>& keys);

}  // namespace silk
