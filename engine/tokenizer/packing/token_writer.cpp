// SPDX-License-Identifier: MIT
// LayeredStream -> token ids (token_format.md §8.2-§8.3).
#include "tokenizer/packing/token_writer.h"

#include "tokenizer/adjacency/between_layer_cases.h"
#include "tokenizer/packing/vertex_codec.h"
#include "tokenizer/vocabulary_layout.h"

namespace silk {

std::vector<int32_t> WriteTokenStream(const LayeredStream& stream) {
  std::vector<int32_t> ids;
  size_t estimate = 0;
  for (const auto& c : stream.components)
    for (const auto& l : c.layers) estimate += l.vertices.size() * 5 + 1;
  ids.reserve(estimate + stream.components.size());
  for (const StreamComponent& comp : stream.components) {
    ids.push_back(vocab::kCBegin);
    for (size_t L = 0; L < comp.layers.size(); ++L) {
      for (const StreamVertex& v : comp.layers[L].vertices) {
        ids.push_back(BlockTokenOf(v.pos));  // block always emitted (quirk §14.C.7)
        ids.push_back(OffsetTokenOf(v.pos));
        if (L == 0) continue;  // the root has only its V tokens
        ids.push_back(vocab::kSBegin + v.window);
        for (int32_t e : v.extras) ids.push_back(vocab::kXBegin + e);
        for (const BetweenToken& b : v.between) ids.push_back(vocab::kBBegin + kBetweenCases * b.start + b.kase);
      }
      ids.push_back(L + 1 < comp.layers.size() ? vocab::kUBegin : vocab::kEBegin);
    }
  }
  return ids;
}

}  // namespace silk
