// SPDX-License-Identifier: MIT
// Self-layer matrix encoder (token_format.md §6): window bits for forward distances 1..8, extras for
// 9..n-9; distances >= n-8 are stated by the partner row's window and never emitted.
#include "tokenizer/adjacency/self_layer_encoder.h"

#include <algorithm>

#include "tokenizer/vocabulary_layout.h"

namespace silk {

void EncodeSelfLayerRow(int32_t n, const std::vector<int32_t>& forward_distances, int32_t* window,
                        std::vector<int32_t>* extras) {
  constexpr int32_t W = vocab::k_self_window;
  int32_t w = 0;
  extras->clear();
  for (int32_t d : forward_distances) {
    if (d <= W) {
      w |= 1 << (d - 1);
    } else if (n > 2 * W + 1 && d <= n - 1 - W) {
      extras->push_back(d - 1);
    }
  }
  std::sort(extras->begin(), extras->end());
  *window = w;
}

}  // namespace silk
