// SPDX-License-Identifier: MIT
// The length budget (token_format.md §9, max_length): the fewest tokens that still finish the sequence from
// the current state, and the one bound beyond which no completion can hit the cap. Read by the
// budget predicates of the rule table (grammar_gates.cpp, grammar_predicates.cpp).
#include <algorithm>

#include "decoder/grammar.h"
#include "decoder/grammar_limits.h"

namespace silk {

using namespace grammar_limits;  // NOLINT: the grammar's own constants

// Tokens needed by rows from_row..n_size-1 if each is K O S B plus its required X values.
int64_t Grammar::FutureRowsCost(int32_t from_row, int32_t n_size) const {
  int64_t c = 0;
  for (int32_t r = std::max(from_row, 0); r < n_size; ++r) c += 4 + incoming_count_[r];
  return c;
}

// Far from the length limit every completion of the current layer fits, so the exact budget
// checks can be skipped: the costliest completion (this row's echoes and B, K O S B for each
// later row up to kMaxLayerSize, every stated echo, a new forward X's echo, E, EOS, plus `extra`
// reserved tokens) stays below this one bound. The single threshold of all budget fast paths.
bool Grammar::FarFromCap(int64_t extra) const {
  return remaining() >= 4 * int64_t{kMaxLayerSize} + 2 * static_cast<int64_t>(incoming_total_) + 16 + extra;
}

// Phase kAfterS: fewest tokens that end the sequence if the layer closes with n_size vertices:
// the current row's missing echoes (canonical) and its B, `future` = FutureRowsCost(b+1,
// n_size) for the later rows (K O S, their echoes, B), then E and EOS. Every token of this
// completion is admitted by the mask, so it is the exact minimum the budget checks use.
int64_t Grammar::RowFinishCost(int32_t n_size, int64_t future) const {
  const bool canonical = options_.window_rule == WindowRule::kCanonical;
  const int64_t missing = canonical ? g_count_ - matched_[n_size] : 0;
  return missing + 1 + future + 2;
}

// Largest layer size whose completion fits the length budget, given `row_rest` tokens still
// needed by the current row (after the token being accepted) and `extra` reserved tokens.
int32_t Grammar::BudgetMaxSize(int64_t extra) const {
  const int64_t rem = remaining();
  if (FarFromCap(extra)) return kMaxLayerSize;
  const int32_t b = static_cast<int32_t>(cur_layer().vertices.size()) - 1;
  int64_t cost = extra + 2;  // E + EOS
  int32_t best = b;          // closing right after the current row
  if (cost > rem) return b - 1;
  for (int32_t n = b + 1; n < kMaxLayerSize; ++n) {
    cost += 4 + incoming_count_[n];
    if (cost > rem) break;
    best = n;
  }
  return best + 1;
}

}  // namespace silk
