// SPDX-License-Identifier: MIT
// Self-layer matrix encoder (token_format.md §6): one row of a layer's adjacency -> window value + extra
// tokens. Mirror of self_layer_decoder.
#pragma once
#include <cstdint>
#include <vector>

namespace silk {

// Row i of a layer of size n. forward_distances: d = (j - i) mod n in [1, n-1] for every
// same-layer neighbour j (any order). Writes the 8-bit window (distances 1..8) and the extra
// values e = d - 1 for 9 <= d <= n - 9 (only when n >= 18), increasing.
void EncodeSelfLayerRow(int32_t n, const std::vector<int32_t>& forward_distances, int32_t* window,
                        std::vector<int32_t>* extras);

}  // namespace silk
