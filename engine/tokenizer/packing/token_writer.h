// SPDX-License-Identifier: MIT
// LayeredStream -> token ids (token_format.md §8): the packing order C, root, U, layers, E.
// Mirror of token_reader.
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

#include "tokenizer/layering/layered_stream.h"

namespace silk {

std::vector<int32_t> WriteTokenStream(const LayeredStream& stream);

}  // namespace silk
