// SPDX-License-Identifier: MIT
// Between-layer matrix encoder (token_format.md §7.1): one row (a vertex's neighbours in the previous
// layer) -> between-layer tokens. Mirror of between_layer_decoder.
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

#include "tokenizer/layering/layered_stream.h"

namespace silk {

// prev_n: size of the previous layer; columns: sorted, distinct previous-layer positions.
void EncodeBetweenLayerRow(int32_t prev_n, const std::vector<int32_t>& columns, std::vector<BetweenToken>* out);

}  // namespace silk
