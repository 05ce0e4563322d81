// SPDX-License-Identifier: MIT
// Coordinate mapping of golden faces onto a decoded component graph (see truth_mapping.h).
#include "truth_mapping.h"

#include <map>
#include <set>
#include <tuple>

#include "tokenizer/adjacency/layer_adjacency.h"

namespace silk::testing {
namespace {
std::tuple<int32_t, int32_t, int32_t> T(const QVec& q) { return {q.x, q.y, q.z}; }
}  // namespace

ComponentLayers LayersOfComponent(const StreamComponent& comp) {
  ComponentLayers layers;
  int32_t prev = 0;
  for (size_t l = 0; l < comp.layers.size(); ++l) {
    std::vector<QVec> pos;
    for (const auto& v : comp.layers[l].vertices) pos.push_back(v.pos);
    if (l > 0) {
      auto adj = DecodeLayerAdjacency(comp.layers[l], prev);
      layers.adjacency.push_back(adj.ok() ? *adj : LayerAdjacency{});
    }
    prev = static_cast<int32_t>(pos.size());
    layers.layer_positions.push_back(pos);
  }
  return layers;
}

std::vector<std::array<int32_t, 3>> TruthOnGraph(const ComponentGraph& g, const std::vector<CoordFace>& faces,
                                                 const std::vector<CoordFace>& excluded) {
  std::map<std::tuple<int32_t, int32_t, int32_t>, int32_t> id, count;
  for (int32_t v = 0; v < g.vertex_count; ++v) {
    ++count[T(g.positions[static_cast<size_t>(v)])];
    id[T(g.positions[static_cast<size_t>(v)])] = v;
  }
  std::set<std::array<std::tuple<int32_t, int32_t, int32_t>, 3>> skip;
  for (const auto& f : excluded) skip.insert({T(f[0]), T(f[1]), T(f[2])});
  std::vector<std::array<int32_t, 3>> out;
  for (const auto& f : faces) {
    if (skip.count({T(f[0]), T(f[1]), T(f[2])})) continue;
    std::array<int32_t, 3> t{};
    bool ok = true;
    for (int k = 0; k < 3 && ok; ++k) {
      auto it = id.find(T(f[k]));
      ok = it != id.end() && count[T(f[k])] == 1;
      if (ok) t[k] = it->second;
    }
    if (ok && g.EdgeOf(t[0], t[1]) >= 0 && g.EdgeOf(t[1], t[2]) >= 0 && g.EdgeOf(t[0], t[2]) >= 0) out.push_back(t);
  }
  return out;
}

}  // namespace silk::testing
