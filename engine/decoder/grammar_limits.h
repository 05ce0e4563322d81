// SPDX-License-Identifier: MIT
// The grammar's limits and window widths, all read from the vocabulary layout (generated from
// tokenizer/vocabulary_layout.json), so Accept, the legal mask and the close checks share them.
// (B window width and cases: tokenizer/adjacency/between_layer_cases.h, from the same layout.)
#pragma once
#include <cstdint>

#include "tokenizer/vocabulary_layout.h"

namespace silk::grammar_limits {

constexpr int32_t kMaxLayerSize = vocab::k_layer_vertex_limit;      // 200 vertices (token_format.md §1.3)
constexpr int32_t kMaxLayerIndex = vocab::k_layer_count_limit - 1;  // 199 (token_format.md §5.3)
constexpr int32_t kSelfWindow = vocab::k_self_window;               // S bits: distances 1..8 (§6)
constexpr int32_t kWindowValues = 1 << kSelfWindow;                 // 256 S ids
// X values (§6): a forward X states a pair beyond the window (distance e+1 > kSelfWindow), its
// echo states the same pair from the other side, so e lies in [kSelfWindow, N - kXMargin].
constexpr int32_t kMinX = kSelfWindow;
constexpr int32_t kXMargin = kSelfWindow + 2;
constexpr int32_t kMaxX = kMaxLayerSize - kXMargin;  // 190
// C, root K O, U, two vertices K O S B (layer 1 needs N >= 2), E.
constexpr int32_t kMinComponentTokens = 1 + 2 + 1 + 2 * 4 + 1;

}  // namespace silk::grammar_limits
