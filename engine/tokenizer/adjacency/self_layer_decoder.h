// SPDX-License-Identifier: MIT
// Self-layer matrix decoding (token_format.md §6): S window + X extra tokens of every vertex of a
// layer -> the layer's in-layer edges. Mirror of self_layer_encoder.
#pragma once
#include <cstdint>
#include <utility>
#include <vector>

#include "core/status.h"
#include "tokenizer/layering/layered_stream.h"

namespace silk {

// In-layer pairs (i, j), i < j, sorted and unique: the logical OR of both rows' statements
// (§6 "Decoding"). Errors (kParseError) for what the encoder never emits: window bits at a
// distance >= N, X values outside [8, N-10] or not increasing.
StatusOr<std::vector<std::pair<int32_t, int32_t>>> DecodeSelfLayer(const StreamLayer& layer);

}  // namespace silk
