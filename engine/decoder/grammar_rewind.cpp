// SPDX-License-Identifier: MIT
// Rewinding the grammar to a prefix (restore the last layer-start checkpoint, replay the rest
// of that layer), and CheckTokens, the whole-array check behind `silktok check`.
#include <algorithm>
#include <vector>

#include "decoder/grammar.h"

namespace silk {

Status Grammar::Rewind(size_t prefix) {
  if (prefix > history_.size()) return InvalidArgument("rewind past the end of the accepted tokens");
  if (prefix == history_.size()) return Status::Ok();
  const std::vector<int32_t> saved = history_;
  size_t idx = checkpoints_.size();
  while (idx > 0 && checkpoints_[idx - 1].token_index > prefix) --idx;
  size_t from = 0;
  if (idx == 0) {
    Reset();
  } else {
    const Checkpoint cp = checkpoints_[idx - 1];
    checkpoints_.resize(idx);
    history_.resize(cp.token_index);
    phase_ = cp.phase;
    layer_ = cp.layer;
    n_prev_ = cp.n_prev;
    closed_layers_ = cp.closed_layers;
    vertices_total_ = cp.vertices_total;
    stream_.components.resize(cp.components);
    auto& layers = stream_.components.back().layers;
    layers.resize(static_cast<size_t>(cp.layer) + 1);
    layers.back().vertices.clear();
    findings_.resize(cp.findings);
    ResetLayerState();
    from = cp.token_index;
  }
  mask_valid_ = false;
  Status st = Status::Ok();
  for (size_t i = from; i < prefix; ++i) {
    Rejection r = Accept(saved[i]);
    if (!r.ok()) {
      st = InternalError("rewind replay refused " + r.message);
      break;
    }
  }
  return st;
}

Rejection CheckTokens(const std::vector<int32_t>& ids, const GrammarOptions& options, size_t* position,
                      bool require_end) {
  Grammar g(options);
  for (size_t i = 0; i < ids.size(); ++i) {
    Rejection r = g.Accept(ids[i]);
    if (!r.ok()) {
      if (position) *position = i;
      return r;
    }
  }
  if (require_end && !g.CanEnd() && !g.Ended()) {
    if (position) *position = ids.size();
    return Rejection{RejectReason::kIncomplete,
                     "token " + std::to_string(ids.size()) +
                         ": the ids end inside a component (token_format.md §11.1: a sequence ends after E)"};
  }
  return Rejection{};
}

}  // namespace silk
