// SPDX-License-Identifier: MIT
// Derives the introducer of every vertex (its first neighbour in the previous layer) and
// turns runs of equal introducers into oriented hint faces.
#include "tokenizer/face_recovery/layering_hints.h"

namespace silk {

std::vector<std::array<int32_t, 3>> LayeringHintFaces(const ComponentGraph& g) {
  std::vector<std::array<int32_t, 3>> hints;
  const int32_t layer_count = static_cast<int32_t>(g.layer_start.size()) - 1;
  std::vector<int32_t> intro(g.vertex_count, -1);
  for (int32_t v = 0; v < g.vertex_count; ++v) {
    const int32_t l = g.layer_of[v];
    for (int32_t w : g.neighbors[v]) {  // sorted: the first one in layer l-1 has the lowest position
      if (g.layer_of[w] == l - 1) {
        intro[v] = w;
        break;
      }
    }
  }
  for (int32_t l = 1; l < layer_count; ++l) {
    for (int32_t x = g.layer_start[l]; x + 1 < g.layer_start[l + 1]; ++x) {
      const int32_t y = x + 1;
      const int32_t u = intro[x];
      if (u < 0 || intro[y] != u || g.EdgeOf(x, y) < 0) continue;
      hints.push_back({u, x, y});
    }
  }
  return hints;
}

}  // namespace silk
