// SPDX-License-Identifier: MIT
// Builds the component's edge graph from per-layer adjacency and enumerates its 3-cycles by
// sorted-neighbour intersection (each triangle once, corners ascending). Zero-area 3-cycles
// (collinear corners) are left out: the encoder drops such faces (§2.4), so none is a face.
#include "tokenizer/face_recovery/component_graph.h"

#include <algorithm>
#include <string>
#include <utility>

#include "tokenizer/cleanup/collinear.h"

namespace silk {
namespace {

// Layer 0 must hold exactly the root, and each later layer needs its adjacency.
Status CheckLayerShapes(const ComponentLayers& layers) {
  const int32_t layer_count = static_cast<int32_t>(layers.layer_positions.size());
  if (layer_count < 1 || layers.layer_positions[0].size() != 1) {
    return InvalidArgument("component must start with a layer 0 holding exactly the root");
  }
  if (static_cast<int32_t>(layers.adjacency.size()) != layer_count - 1) {
    return InvalidArgument("component needs one adjacency per layer >= 1 (" + std::to_string(layer_count - 1) +
                           "), got " + std::to_string(layers.adjacency.size()));
  }
  return Status::Ok();
}

// Vertex ids in reading order: layer by layer, with their layer and position.
void PlaceLayerVertices(const ComponentLayers& layers, ComponentGraph& g) {
  const int32_t layer_count = static_cast<int32_t>(layers.layer_positions.size());
  for (int32_t l = 0; l < layer_count; ++l) {
    g.layer_start.push_back(g.vertex_count);
    const int32_t n = static_cast<int32_t>(layers.layer_positions[l].size());
    g.vertex_count += n;
    g.layer_of.insert(g.layer_of.end(), n, l);
    g.positions.insert(g.positions.end(), layers.layer_positions[l].begin(), layers.layer_positions[l].end());
  }
  g.layer_start.push_back(g.vertex_count);
}

// Layer l's decoded edges (self pairs, then pairs with layer l-1) as neighbour entries both ways.
Status AddLayerEdges(const LayerAdjacency& adj, int32_t l, ComponentGraph& g) {
  const int32_t n = g.layer_start[l + 1] - g.layer_start[l];
  const int32_t np = g.layer_start[l] - g.layer_start[l - 1];
  for (const auto& [i, j] : adj.self_edges) {
    if (i < 0 || j < 0 || i >= n || j >= n || i == j) {
      return InvalidArgument("layer " + std::to_string(l) + ": self edge (" + std::to_string(i) + ", " +
                             std::to_string(j) + ") outside the layer of " + std::to_string(n));
    }
    g.neighbors[g.layer_start[l] + i].push_back(g.layer_start[l] + j);
    g.neighbors[g.layer_start[l] + j].push_back(g.layer_start[l] + i);
  }
  for (const auto& [i, j] : adj.between_edges) {
    if (i < 0 || j < 0 || i >= n || j >= np) {
      return InvalidArgument("layer " + std::to_string(l) + ": between edge (" + std::to_string(i) + ", " +
                             std::to_string(j) + ") outside layers of " + std::to_string(n) + " / " +
                             std::to_string(np));
    }
    g.neighbors[g.layer_start[l] + i].push_back(g.layer_start[l - 1] + j);
    g.neighbors[g.layer_start[l - 1] + j].push_back(g.layer_start[l] + i);
  }
  return Status::Ok();
}

// Sorts and dedupes the neighbour lists and numbers the edges (a, b), a < b, by a then b.
void IndexEdges(ComponentGraph& g) {
  for (int32_t v = 0; v < g.vertex_count; ++v) {
    auto& nb = g.neighbors[v];
    std::sort(nb.begin(), nb.end());
    nb.erase(std::unique(nb.begin(), nb.end()), nb.end());
    for (int32_t w : nb) {
      if (w <= v) continue;
      g.edge_index.emplace((static_cast<uint64_t>(v) << 32) | static_cast<uint32_t>(w),
                           static_cast<int32_t>(g.edges.size()));
      g.edges.push_back({v, w});
    }
  }
}

// The non-collinear 3-cycles, each once with corners ascending, linked to their edges.
Status EnumerateTriangles(ComponentGraph& g) {
  g.edge_triangles.resize(g.edges.size());
  std::vector<int32_t> common;
  int64_t work = 0;
  for (int32_t e = 0; e < static_cast<int32_t>(g.edges.size()); ++e) {
    const auto [a, b] = g.edges[e];
    const auto& na = g.neighbors[a];
    const auto& nb = g.neighbors[b];
    work += static_cast<int64_t>(na.size() + nb.size());
    if (work > kMaxComponentGraphWork) {
      return LimitExceeded("component edge graph too dense for face recovery");
    }
    common.clear();
    std::set_intersection(na.begin(), na.end(), nb.begin(), nb.end(), std::back_inserter(common));
    for (int32_t c : common) {
      if (c <= b) continue;
      if (Collinear(g.positions[static_cast<size_t>(a)], g.positions[static_cast<size_t>(b)],
                    g.positions[static_cast<size_t>(c)]))
        continue;
      if (static_cast<int64_t>(g.triangles.size()) >= kMaxComponentTriangles) {
        return LimitExceeded("component has more than " + std::to_string(kMaxComponentTriangles) +
                             " 3-cycles; not a mesh the encoder can produce");
      }
      const int32_t t = static_cast<int32_t>(g.triangles.size());
      g.triangles.push_back({a, b, c});
      const int32_t bc = g.EdgeOf(b, c), ac = g.EdgeOf(a, c);
      g.triangle_edges.push_back({e, bc, ac});
      g.edge_triangles[e].push_back(t);
      g.edge_triangles[bc].push_back(t);
      g.edge_triangles[ac].push_back(t);
    }
  }
  return Status::Ok();
}

}  // namespace

StatusOr<ComponentGraph> BuildComponentGraph(const ComponentLayers& layers) {
  SILK_RETURN_IF_ERROR(CheckLayerShapes(layers));
  ComponentGraph g;
  PlaceLayerVertices(layers, g);
  g.neighbors.resize(g.vertex_count);
  for (int32_t l = 1; l < static_cast<int32_t>(layers.layer_positions.size()); ++l)
    SILK_RETURN_IF_ERROR(AddLayerEdges(layers.adjacency[l - 1], l, g));
  IndexEdges(g);
  SILK_RETURN_IF_ERROR(EnumerateTriangles(g));
  return g;
}

}  // namespace silk
