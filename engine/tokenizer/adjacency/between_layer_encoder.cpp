// SPDX-License-Identifier: MIT
// Between-layer matrix encoder (token_format.md §7.1): scan the zero-padded row; each 1 starts a token
// whose 5-wide window is a case of §7.2, truncated before a window's extra run of ones.
#include "tokenizer/adjacency/between_layer_encoder.h"

#include "tokenizer/adjacency/between_layer_cases.h"

namespace silk {
namespace {

// Number of runs of ones in a 5-bit window (bit p-1 = position p) and the position where
// run `which` (1-based) starts; 0 if there is no such run.
int RunStart(int32_t w, int which) {
  int runs = 0;
  bool in_run = false;
  for (int p = 1; p <= kBetweenWindow; ++p) {
    const bool one = (w >> (p - 1)) & 1;
    if (one && !in_run && ++runs == which) return p;
    in_run = one;
  }
  return 0;
}

}  // namespace

void EncodeBetweenLayerRow(int32_t prev_n, const std::vector<int32_t>& columns, std::vector<BetweenToken>* out) {
  out->clear();
  std::vector<char> row(static_cast<size_t>(prev_n) + kBetweenWindow + 1, 0);
  for (int32_t c : columns) row[static_cast<size_t>(c)] = 1;
  for (int32_t s = 0; s < prev_n; ++s) {
    if (!row[static_cast<size_t>(s)]) continue;
    int32_t w = 0;
    for (int p = 1; p <= kBetweenWindow; ++p)
      if (row[static_cast<size_t>(s + p)]) w |= 1 << (p - 1);
    int32_t kase = BetweenCaseOfPattern(w);
    int consumed = kBetweenWindow;
    if (kase < 0) {
      // Too many runs: cut before the offending run (3rd if the window starts with 1, else 2nd).
      const int p_star = RunStart(w, (w & 1) ? 3 : 2);
      const int32_t truncated = w & ((1 << (p_star - 1)) - 1);
      kase = BetweenCaseOfPattern(truncated);
      consumed = p_star - 1;
    }
    out->push_back(BetweenToken{s, kase});
    for (int p = 1; p <= consumed; ++p) row[static_cast<size_t>(s + p)] = 0;
  }
}

}  // namespace silk
