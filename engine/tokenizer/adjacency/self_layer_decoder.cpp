// SPDX-License-Identifier: MIT
// Self-layer decoder: row i's window bit d-1 and extra value d-1 both mean "v_i is adjacent
// to v_{(i+d) mod N}" (token_format.md §6); both rows' statements are OR-ed into one undirected set.
#include "tokenizer/adjacency/self_layer_decoder.h"

#include <algorithm>
#include <string>

#include "tokenizer/vocabulary_layout.h"

namespace silk {

StatusOr<std::vector<std::pair<int32_t, int32_t>>> DecodeSelfLayer(const StreamLayer& layer) {
  const int32_t n = static_cast<int32_t>(layer.vertices.size());
  std::vector<std::pair<int32_t, int32_t>> pairs;
  auto add = [&](int32_t i, int32_t d) {
    const int32_t j = (i + d) % n;
    pairs.emplace_back(std::min(i, j), std::max(i, j));
  };
  for (int32_t i = 0; i < n; ++i) {
    const StreamVertex& v = layer.vertices[i];
    if (v.window < 0 || v.window >= (1 << vocab::k_self_window)) {
      return ParseError("self-layer row " + std::to_string(i) + ": window value " + std::to_string(v.window) +
                        " is not an 8-bit value");
    }
    for (int32_t d = 1; d <= vocab::k_self_window; ++d) {
      if (!((v.window >> (d - 1)) & 1)) continue;
      if (d >= n) {
        return ParseError("self-layer row " + std::to_string(i) + ": window bit " + std::to_string(d - 1) +
                          " points past the end of a layer of " + std::to_string(n) + " vertices");
      }
      add(i, d);
    }
    int32_t last = -1;
    for (int32_t e : v.extras) {
      if (e < vocab::k_self_window || e > n - 10) {
        return ParseError("self-layer row " + std::to_string(i) + ": extra value " + std::to_string(e) +
                          " outside [8, N-10] for a layer of " + std::to_string(n) + " vertices");
      }
      if (e <= last) {
        return ParseError("self-layer row " + std::to_string(i) + ": extra values not increasing");
      }
      last = e;
      add(i, e + 1);
    }
  }
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
  return pairs;
}

}  // namespace silk
