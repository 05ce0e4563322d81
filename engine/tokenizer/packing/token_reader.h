// SPDX-License-Identifier: MIT
// ids -> LayeredStream: the strict inverse of token_writer. Only sequences the encoder can
// produce (token_format.md §8.3, §11) are accepted; anything else is an error naming the token.
#pragma once
#include <cstdint>
#include <vector>

#include "core/status.h"
#include "tokenizer/layering/layered_stream.h"

namespace silk {

// Longest id array ReadTokenStream accepts (bounds work and memory on arbitrary input).
inline constexpr int64_t kMaxReadTokens = 1 << 20;

// Parses `ids` (no BOS/EOS/PAD) into components / layers / vertices. Checks the grammar of
// token_format.md §11 including the deferred per-layer conditions (window bits and X values inside the
// layer, B segments inside the previous layer, continuation starts, layer 1 = "460" rows,
// size and count limits). Errors are kParseError "token P (id I): why" (or kLimitExceeded
// for over-long input). Linear time, allocation proportional to the input.
// The same function backs silk::ReadTokenStream (tokenizer.h).
StatusOr<LayeredStream> ReadTokens(const std::vector<int32_t>& ids);

}  // namespace silk
