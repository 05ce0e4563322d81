// SPDX-License-Identifier: MIT
// The gates of the rule table: predicates that hold for every id of a class or for none (the
// length cap, a closable layer, room for one more vertex...). Step calls them to judge one id,
// the legal mask calls the same functions to decide whether a whole class is open.
#include <algorithm>
#include <string>

#include "decoder/grammar.h"
#include "decoder/grammar_limits.h"

namespace silk {

using namespace grammar_limits;  // NOLINT: the grammar's own constants

Rejection Grammar::NotEnded(int32_t id) const {
  if (phase_ != GrammarPhase::kEnded) return Rejection{};
  return Reject(RejectReason::kAfterEos, id, [&] { return std::string("nothing may follow EOS"); });
}

// token_format.md §9: at most max_length tokens including EOS.
Rejection Grammar::RoomForToken(int32_t id) const {
  if (options_.max_length <= 0 || static_cast<int64_t>(history_.size()) + 1 <= options_.max_length) return Rejection{};
  return Reject(RejectReason::kTooLong, id, [&] { return std::string("sequence longer than the length limit"); });
}

// C: the component's smallest completion (root, U, two vertices, E) and EOS must fit.
Rejection Grammar::RoomForComponent(int32_t id) const {
  if (remaining() - 1 >= kMinComponentTokens) return Rejection{};
  return Reject(RejectReason::kTooLong, id, [&] { return std::string("no room left for a whole component"); });
}

// E right after the root (phase kWantU0) is never legal: a component needs layer 1 (token_format.md §8.3).
Rejection Grammar::RefuseEndAfterRoot(int32_t id) const {
  return Reject(RejectReason::kLayerZeroSize, id, [&] {
    return std::string("E directly after the root: a component needs layer 1 (token_format.md §8.3)");
  });
}

// U/E: the deferred rules of token_format.md §11.2 hold at the layer's current size.
Rejection Grammar::LayerClosable(int32_t id) const {
  const int32_t n = static_cast<int32_t>(cur_layer().vertices.size());
  if (sizes_.Test(n)) return Rejection{};
  return Reject(RejectReason::kLayerNotClosable, id,
                [&] { return "layer of " + std::to_string(n) + " vertices cannot close: " + ExplainClose(n); });
}

Rejection Grammar::BelowLayerIndexLimit(int32_t id) const {
  if (layer_ < kMaxLayerIndex) return Rejection{};
  return Reject(RejectReason::kTooManyLayers, id,
                [&] { return std::string("layer index 200 would follow (token_format.md §5.3)"); });
}

// U: the next layer's cheapest content (K O S B) and E, EOS must fit.
Rejection Grammar::RoomForLayer(int32_t id) const {
  if (remaining() - 1 >= 4 + 1 + 1) return Rejection{};
  return Reject(RejectReason::kTooLong, id, [&] { return std::string("no room for another layer"); });
}

// E: EOS must still fit after it.
Rejection Grammar::RoomForEos(int32_t id) const {
  if (remaining() - 1 >= 1) return Rejection{};
  return Reject(RejectReason::kTooLong, id, [&] { return std::string("no room for EOS after E"); });
}

// K after a finished vertex (token_format.md §1.3): at most 200 vertices per layer.
Rejection Grammar::BelowLayerSizeLimit(int32_t id) const {
  if (static_cast<int32_t>(cur_layer().vertices.size()) < kMaxLayerSize) return Rejection{};
  return Reject(RejectReason::kLayerTooLarge, id,
                [&] { return std::string("a layer holds at most 200 vertices (token_format.md §1.3)"); });
}

// K after a finished vertex: some larger size must still close the layer (token_format.md §11.2), and the
// rows up to it (K O S B and their echoes) plus E, EOS must fit.
Rejection Grammar::RoomForVertex(int32_t id) const {
  const int32_t n = static_cast<int32_t>(cur_layer().vertices.size());
  const int32_t next = sizes_.Next(n + 1);
  if (next < 0 && !FarFromCap())
    return Reject(RejectReason::kTooLong, id,
                  [&] { return std::string("no room left for another vertex and the layer's end"); });
  if (next < 0)
    return Reject(RejectReason::kNotCanonical, id, [&] {
      return "the earlier rows of this layer only fit a layer of " + std::to_string(n) + " vertices";
    });
  if (remaining() < FutureRowsCost(n, next) + 2)
    return Reject(RejectReason::kTooLong, id,
                  [&] { return std::string("no room left for another vertex and the layer's end"); });
  return Rejection{};
}

// A continuation B: the layer must still close within the cap at the smallest size left.
Rejection Grammar::RoomToCloseAfterB(int32_t id) const {
  const int32_t n = static_cast<int32_t>(cur_layer().vertices.size());
  if (FarFromCap() || remaining() - 1 >= FutureRowsCost(n, std::max(n, sizes_.Next(n))) + 2) return Rejection{};
  return Reject(RejectReason::kTooLong, id, [&] { return std::string("no room left to close the layer"); });
}

// The first B ends the row's X list: the sizes it leaves are those at which every due echo was
// given (canonical, §11.2 pairs stated twice) and whose completion fits the cap. Writes them to
// next_sizes_ for ApplyFirstB.
Rejection Grammar::RowCanFinish(int32_t id) const {
  const bool canonical = options_.window_rule == WindowRule::kCanonical;
  const int32_t budget_max = BudgetMaxSize(1);
  LayerSizeSet& fin = next_sizes_;
  fin.Clear();
  if (!canonical || g_count_ == 0) {
    fin = row_sizes_;
    fin.KeepAtMost(budget_max);
  } else {
    for (int32_t n = row_sizes_.Next(0); n >= 0 && n <= budget_max; n = row_sizes_.Next(n + 1))
      if (matched_[n] == g_count_) fin.Set(n);
  }
  if (!fin.Empty()) return Rejection{};
  if (budget_max < kMaxLayerSize)
    return Reject(RejectReason::kTooLong, id, [&] { return std::string("no room left to finish the layer"); });
  return Reject(RejectReason::kNotCanonical, id, [&] {
    return std::string(
        "the vertex's X values miss a pair an earlier row states (token_format.md §11.2 canonical consistency)");
  });
}

}  // namespace silk
