// SPDX-License-Identifier: MIT
// Whole-fan edits for the verification search: replace every face at the root by its fan
// (fixed by layer 1 = R(root)), then regrow the rest.
#pragma once
#include <cstdint>
#include <vector>

#include "tokenizer/face_recovery/component_graph.h"
#include "tokenizer/face_recovery/face_search_edits.h"

namespace silk {

// The root's fan edits, as growth constraints: the fan's faces forced first, every other
// triangle at the root forbidden, the rest regrown (on top of from.constraints and from
// scratch). Layer 1 in order is R(root), so the fan is (0, l_k, l_k+1), closed by
// (0, l_last, l_0) when the root is interior (both are tried when that edge exists).
void RootFanEdits(const ComponentGraph& g, const SearchCandidate& from, int64_t lookahead_budget,
                  std::vector<GrowConstraints>* out);

}  // namespace silk
