// SPDX-License-Identifier: MIT
// Between-layer decoder: expands every (start, case) token of a row into its columns using
// the shared 26-case table; the encoder's segments never overlap, so this is its inverse.
#include "tokenizer/adjacency/between_layer_decoder.h"

#include <algorithm>
#include <string>

#include "tokenizer/adjacency/between_layer_cases.h"

namespace silk {

StatusOr<std::vector<std::pair<int32_t, int32_t>>> DecodeBetweenLayer(const StreamLayer& layer, int32_t prev_size) {
  const int32_t n = static_cast<int32_t>(layer.vertices.size());
  std::vector<std::pair<int32_t, int32_t>> pairs;
  for (int32_t i = 0; i < n; ++i) {
    const auto& row = layer.vertices[i].between;
    if (row.empty()) return ParseError("between-layer row " + std::to_string(i) + " has no B token");
    for (size_t k = 0; k < row.size(); ++k) {
      const BetweenToken& t = row[k];
      const std::string where = "between-layer row " + std::to_string(i) + ", token " + std::to_string(k);
      if (t.kase < 0 || t.kase >= kBetweenCases || t.start < 0) {
        return ParseError(where + ": no such start/case (" + std::to_string(t.start) + ", " + std::to_string(t.kase) +
                          ")");
      }
      if (t.start + BetweenCaseLastOne(t.kase) > prev_size - 1) {
        return ParseError(where + ": segment reaches past the previous layer of " + std::to_string(prev_size) +
                          " vertices");
      }
      if (k > 0 && t.start < BetweenNextMinStart(row[k - 1].start, row[k - 1].kase)) {
        return ParseError(where + ": start column overlaps the previous token's window");
      }
      pairs.emplace_back(i, t.start);
      const int32_t bits = BetweenCasePattern(t.kase);
      for (int32_t p = 1; p <= kBetweenWindow; ++p) {
        if ((bits >> (p - 1)) & 1) pairs.emplace_back(i, t.start + p);
      }
    }
  }
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
  return pairs;
}

}  // namespace silk
