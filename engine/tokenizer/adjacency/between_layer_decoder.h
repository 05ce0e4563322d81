// SPDX-License-Identifier: MIT
// Between-layer matrix decoding (token_format.md §7.3): the B tokens of every vertex of layer L ->
// the edges between layer L and layer L-1. Mirror of between_layer_encoder.
#pragma once
#include <cstdint>
#include <utility>
#include <vector>

#include "core/status.h"
#include "tokenizer/layering/layered_stream.h"

namespace silk {

// Pairs (i in `layer`, j in the previous layer of `prev_size` vertices), sorted, unique.
// Each token (s, c) sets column s and the columns s+p of case c's window (§7.2). Errors
// (kParseError): a row without B tokens, segments reaching past the previous layer, starts
// that break the continuation rule of §7.3, case ids out of range.
StatusOr<std::vector<std::pair<int32_t, int32_t>>> DecodeBetweenLayer(const StreamLayer& layer, int32_t prev_size);

}  // namespace silk
