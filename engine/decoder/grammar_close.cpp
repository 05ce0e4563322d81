// SPDX-License-Identifier: MIT
// Closing a layer: the vertex count, the explanation of a refused U/E (which deferred rule
// of token_format.md §11.2 fails at this size) and the findings of WindowRule::kUnion.
#include <algorithm>
#include <string>
#include <vector>

#include "decoder/grammar.h"
#include "decoder/grammar_limits.h"

namespace silk {

using namespace grammar_limits;  // NOLINT: the grammar's own constants

void Grammar::CloseLayer() {
  const int32_t n = static_cast<int32_t>(cur_layer().vertices.size());
  ++closed_layers_;
  vertices_total_ += n;
  if (layer_ > 0 && options_.window_rule == WindowRule::kUnion) RecordFindings();
}

namespace {
bool HasExtra(const StreamVertex& v, int32_t e) {
  for (int32_t x : v.extras)
    if (x == e) return true;
  return false;
}

// How rows a < b of a layer of size n state their pair (token_format.md §11.2): *sa, *sb = 0/1 when the
// pair is covered by both rows (windows for N <= 9-style distances, extras for N >= 18),
// -1 when the rows do not both cover it.
void PairStatements(const std::vector<StreamVertex>& vs, int32_t n, int32_t a, int32_t b, int32_t* sa, int32_t* sb) {
  const int32_t g = b - a;
  *sa = *sb = -1;
  if (g <= kSelfWindow && n - g <= kSelfWindow) {
    *sa = (vs[a].window >> (g - 1)) & 1;
    *sb = (vs[b].window >> (n - g - 1)) & 1;
  } else if (n >= 2 * (kSelfWindow + 1) && g > kSelfWindow && g < n - kSelfWindow) {
    *sa = HasExtra(vs[a], g - 1);
    *sb = HasExtra(vs[b], n - g - 1);
  }
}
}  // namespace

// Pairs stated by one covering row and denied by the other (token_format.md §11.2, §12.2 "token-level
// consistency"): under the union rule they are edges, and each one is a repaired false 0.
void Grammar::RecordFindings() {
  const auto& vs = cur_layer().vertices;
  const int32_t n = static_cast<int32_t>(vs.size());
  const int32_t comp = static_cast<int32_t>(stream_.components.size()) - 1;
  for (int32_t a = 0; a < n; ++a) {
    for (int32_t b = a + 1; b < n; ++b) {
      int32_t sa, sb;
      PairStatements(vs, n, a, b, &sa, &sb);
      if (sa >= 0 && sa != sb) findings_.push_back(WindowFinding{comp, layer_, a, b});
    }
  }
}

std::string Grammar::ExplainClose(int32_t n) const {
  const auto& vs = cur_layer().vertices;
  const bool canonical = options_.window_rule == WindowRule::kCanonical;
  for (int32_t b = 0; b < n; ++b) {
    const auto& v = vs[b];
    if (n <= kSelfWindow && v.window >= (1 << (n - 1)))
      return "row " + std::to_string(b) + " has a window bit at a distance >= N (token_format.md §11.2)";
    if (canonical && layer_ == 1 && b < n - 1 && !(v.window & 1))
      return "layer 1 rows " + std::to_string(b) + " and " + std::to_string(b + 1) +
             " are not adjacent (chain rule, token_format.md §11.2)";
    for (int32_t e : v.extras)
      if (e > n - kXMargin)
        return "row " + std::to_string(b) + " has X value " + std::to_string(e) + " > N-10 (token_format.md §6)";
  }
  if (canonical) {
    for (int32_t a = 0; a < n; ++a)
      for (int32_t b = a + 1; b < n; ++b) {
        int32_t sa, sb;
        PairStatements(vs, n, a, b, &sa, &sb);
        if (sa >= 0 && sa != sb)
          return "rows " + std::to_string(a) + " and " + std::to_string(b) +
                 " disagree about their pair (canonical consistency, token_format.md §11.2)";
      }
  }
  return "a zero-length edge or the length budget";
}

}  // namespace silk
