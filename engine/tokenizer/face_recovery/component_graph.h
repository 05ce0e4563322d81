// SPDX-License-Identifier: MIT
// The decoded edge graph of one component and its 3-cycles: the raw material face
// recovery chooses faces from (token_format.md §10.5: faces are implicit, only edges are encoded).
#pragma once
#include <array>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "core/status.h"
#include "tokenizer/layering/layered_stream.h"

namespace silk {

// Layer-by-layer view of one component: the input of face recovery.
struct ComponentLayers {
  // layer_positions[L][i] = position of vertex i of layer L (layer 0 = the root alone).
  std::vector<std::vector<QVec>> layer_positions;
  // adjacency[L-1] = decoded edges of layer L (L >= 1): self pairs and pairs with layer L-1.
  std::vector<LayerAdjacency> adjacency;
};

// Undirected edge graph with vertex ids in reading order (layer 0 first, then layer 1, ...).
struct ComponentGraph {
  int32_t vertex_count = 0;
  std::vector<int32_t> layer_of;                // per vertex
  std::vector<int32_t> layer_start;             // first vertex id of each layer (+ end)
  std::vector<QVec> positions;                  // per vertex (decoded grid coordinates)
  std::vector<std::vector<int32_t>> neighbors;  // sorted
  std::vector<std::array<int32_t, 2>> edges;    // (a, b), a < b
  std::unordered_map<uint64_t, int32_t> edge_index;
  std::vector<std::array<int32_t, 3>> triangles;       // 3-cycles, sorted corners
  std::vector<std::vector<int32_t>> edge_triangles;    // per edge: triangle ids
  std::vector<std::array<int32_t, 3>> triangle_edges;  // per triangle: edges (ab, bc, ac)

  // Edge id of {a, b}, or -1.
  int32_t EdgeOf(int32_t a, int32_t b) const {
    if (a > b) std::swap(a, b);
    auto it = edge_index.find((static_cast<uint64_t>(a) << 32) | static_cast<uint32_t>(b));
    return it == edge_index.end() ? -1 : it->second;
  }
};

// Most 3-cycles one component may have before recovery gives up (kLimitExceeded): keeps
// arbitrary token streams (fuzzing, bad samples) from taking cubic time.
inline constexpr int64_t kMaxComponentTriangles = 1 << 20;
// Bound on neighbour-list steps spent enumerating 3-cycles (same purpose).
inline constexpr int64_t kMaxComponentGraphWork = int64_t{1} << 27;

// Validates the layer/adjacency shapes (indices inside their layers) and builds the graph.
StatusOr<ComponentGraph> BuildComponentGraph(const ComponentLayers& layers);

}  // namespace silk
