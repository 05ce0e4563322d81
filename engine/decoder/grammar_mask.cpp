// The legal-token mask of the grammar: class ranges OR'ed with the few dynamic ranges of the
// current state (X window, B columns, S values near a layer's end). Mirrors Grammar::Accept.
#include <algorithm>

#include "decoder/grammar.h"
#include "decoder/grammar_limits.h"
#include "tokenizer/between_layer_cases.h"
#include "tokenizer/vertex_codec.h"
#include "tokenizer/vocabulary_layout.h"

namespace silk {
using namespace grammar_limits;  // NOLINT: the grammar's own constants

void Grammar::AddBetweenMask(int32_t min_s) {
  // Spec §11.3: s + ℓ(c) <= N_prev - 1; starts with room >= 5 take all 26 cases.
  const int32_t last = n_prev_ - 1;
  if (min_s > last) return;
  if (!eq_cols_any_) {
    const int32_t full_hi = n_prev_ - 1 - kBetweenWindow;
    if (min_s <= full_hi)
      mask_.SetRange(vocab::kBBegin + kBetweenCases * min_s, vocab::kBBegin + kBetweenCases * (full_hi + 1));
    for (int32_t s = std::max(min_s, full_hi + 1); s <= last; ++s) {
      const int32_t room = last - s;
      for (int32_t c = 0; c < kBetweenCases; ++c)
        if (BetweenCaseLastOne(c) <= room) mask_.Set(vocab::kBBegin + kBetweenCases * s + c);
    }
    return;
  }
  for (int32_t s = min_s; s <= last; ++s)
    for (int32_t c = 0; c < kBetweenCases; ++c)
      if (s + BetweenCaseLastOne(c) <= last && ColumnsClear(s, c)) mask_.Set(vocab::kBBegin + kBetweenCases * s + c);
}

void Grammar::ComputeMask() {
  mask_.Clear();
  const int32_t rem = remaining();
  const bool canonical = options_.window_rule == WindowRule::kCanonical;
  switch (phase_) {
    case GrammarPhase::kStart:
    case GrammarPhase::kAfterE:
      if (phase_ == GrammarPhase::kAfterE) mask_.Set(vocab::k_eos_id);
      if (rem - 1 >= kMinComponentTokens) mask_.Set(vocab::kCBegin);
      break;
    case GrammarPhase::kWantK:
      mask_.SetRange(vocab::kKBegin, vocab::kKEnd);
      break;
    case GrammarPhase::kWantO: {
      mask_.SetRange(vocab::kOBegin, vocab::kOEnd);
      if (layer_ == 0 || !options_.geometric_rules) break;
      const auto& vs = cur_layer().vertices;
      const int32_t b = static_cast<int32_t>(vs.size()) - 1;
      auto drop = [&](const QVec& q) {
        if (BlockTokenOf(q) == pending_block_) mask_.Reset(OffsetTokenOf(q));
      };
      for (int32_t a = std::max(0, b - kSelfWindow); a < b; ++a)
        if ((vs[a].window >> (b - a - 1)) & 1) drop(vs[a].pos);
      for (int32_t g = incoming_[b].Next(0); g >= 0; g = incoming_[b].Next(g + 1)) drop(vs[b - g].pos);
      const auto& pv = prev_layer().vertices;
      bool all_same = true;
      for (const auto& v : pv) all_same = all_same && v.pos == pv[0].pos;
      if (all_same) drop(pv[0].pos);
      break;
    }
    case GrammarPhase::kWantU0:
      mask_.Set(vocab::kUBegin);
      break;
    case GrammarPhase::kWantS: {
      const int32_t b = static_cast<int32_t>(cur_layer().vertices.size()) - 1;
      const int32_t g = incoming_count_[b];
      const int32_t bm = BudgetMaxSize(2 + g);
      bool big = false;
      int32_t small[kSelfWindow];
      int32_t n_small = 0;
      for (int32_t n = sizes_.Next(b + 1); n >= 0 && n <= bm; n = sizes_.Next(n + 1)) {
        if (n >= b + kSelfWindow + 1) {
          big = true;
          break;
        }
        small[n_small++] = n;
      }
      const bool chain = canonical && layer_ == 1;
      if (big && !chain) {
        mask_.SetRange(vocab::kSBegin, vocab::kSEnd);
        break;
      }
      for (int32_t w = 0; w < kWindowValues; ++w) {
        bool legal = big && (w & 1);
        for (int32_t i = 0; i < n_small && !legal; ++i) legal = WindowOk(small[i], w);
        if (legal) mask_.Set(vocab::kSBegin + w);
      }
      break;
    }
    case GrammarPhase::kAfterS: {
      const int32_t b = static_cast<int32_t>(cur_layer().vertices.size()) - 1;
      const int32_t lo = std::max(last_x_ + 1, kMinX);
      // Mirrors the X case of Accept: per size, forward X need cost+2 tokens, a free
      // wrap-around X (kUnion) cost+1, the next echo cost (RowFinishCost).
      const bool tight = !FarFromCap();
      int32_t fwd_hi = -1;
      int64_t future = 0;
      int32_t row = b + 1;
      // Unconstrained and no required values: the largest size bounds the range.
      const int32_t first = (!tight && (g_count_ == 0 || !canonical)) ? row_sizes_.Max() : row_sizes_.Next(0);
      for (int32_t n = first; n >= 0; n = row_sizes_.Next(n + 1)) {
        if (tight)
          for (; row < n; ++row) future += 4 + incoming_count_[row];
        const int64_t cost = tight ? RowFinishCost(n, future) : 0;
        const int32_t xhi = std::min(n - kXMargin, kMaxX);
        if (!tight || cost + 2 <= rem) fwd_hi = std::max(fwd_hi, std::min(xhi, n - 2 - b));
        if (!canonical) {
          const int32_t wlo = std::max(lo, n - 1 - b);
          if ((!tight || cost + 1 <= rem) && wlo <= xhi) mask_.SetRange(vocab::kXBegin + wlo, vocab::kXBegin + xhi + 1);
        } else if (matched_[n] < g_count_ && (!tight || cost <= rem)) {
          const int32_t e = n - 1 - g_desc_[matched_[n]];
          if (e >= lo && e <= xhi) mask_.Set(vocab::kXBegin + e);
        }
      }
      if (fwd_hi >= lo) mask_.SetRange(vocab::kXBegin + lo, vocab::kXBegin + fwd_hi + 1);
      const int32_t bm_b = BudgetMaxSize(1);
      bool can_b = false;
      if (g_count_ == 0 || !canonical) can_b = row_sizes_.Next(0) >= 0 && row_sizes_.Next(0) <= bm_b;
      else
      for (int32_t n = row_sizes_.Next(0); n >= 0 && n <= bm_b && !can_b; n = row_sizes_.Next(n + 1))
        can_b = !canonical || matched_[n] == g_count_;
      if (can_b) AddBetweenMask(0);
      break;
    }
    case GrammarPhase::kAfterB: {
      const int32_t n = static_cast<int32_t>(cur_layer().vertices.size());
      const bool tight = !FarFromCap();
      if (!tight || rem - 1 >= FutureRowsCost(n, std::max(n, sizes_.Next(n))) + 2)
        AddBetweenMask(BetweenNextMinStart(last_s_, last_c_));
      if (n < kMaxLayerSize) {
        const int32_t next = sizes_.Next(n + 1);
        if (next >= 0 && (!tight || rem >= FutureRowsCost(n, next) + 2)) mask_.SetRange(vocab::kKBegin, vocab::kKEnd);
      }
      if (sizes_.Test(n)) {
        if (layer_ < kMaxLayerIndex && rem - 1 >= 6) mask_.Set(vocab::kUBegin);
        if (rem - 1 >= 1) mask_.Set(vocab::kEBegin);
      }
      break;
    }
    case GrammarPhase::kEnded:
      break;
  }
}

const TokenMask& Grammar::LegalMask() {
  if (!mask_valid_) {
    ComputeMask();
    mask_valid_ = true;
  }
  return mask_;
}

int32_t Grammar::NextClosableSize(int32_t from) const {
  // Inside a vertex's X list every size of the row set is still reachable (more X may follow).
  if (phase_ == GrammarPhase::kAfterS) return row_sizes_.Next(from);
  return sizes_.Next(from);
}

int32_t Grammar::Forced() { return LegalMask().Single(); }

}  // namespace silk
