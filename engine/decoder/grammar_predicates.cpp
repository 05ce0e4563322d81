// SPDX-License-Identifier: MIT
// The id-dependent predicates of the rule table, each as a pair over one shared description:
// `Test*` judges one id for Step, `Add*` adds every id of the class it admits to the legal mask.
// The descriptions: the positions the vertex is linked to (O), the sizes a window keeps open
// (S), the X intervals per layer size (X), the cases per B start column (B).
#include <algorithm>
#include <string>

#include "decoder/grammar.h"
#include "decoder/grammar_limits.h"
#include "tokenizer/adjacency/between_layer_cases.h"
#include "tokenizer/packing/vertex_codec.h"
#include "tokenizer/vocabulary_layout.h"

namespace silk {

using namespace grammar_limits;  // NOLINT: the grammar's own constants

// ---- O: the geometric rule (not in the spec's grammar, satisfied by all 154 official streams):
// no edge joins two vertices at one grid position. The positions the vertex being read is
// already linked to: earlier rows of its layer whose window bit or X value states an edge to
// it, and the previous layer's position when every vertex there has it (no B could avoid it).
template <class F>
void Grammar::ForEachLinkedPosition(F&& f) const {
  const auto& vs = cur_layer().vertices;
  const int32_t b = static_cast<int32_t>(vs.size()) - 1;
  for (int32_t a = std::max(0, b - kSelfWindow); a < b; ++a)
    if ((vs[a].window >> (b - a - 1)) & 1) f(vs[a].pos);
  for (int32_t g = incoming_[b].Next(0); g >= 0; g = incoming_[b].Next(g + 1)) f(vs[b - g].pos);
  const auto& pv = prev_layer().vertices;
  for (const auto& v : pv)
    if (v.pos != pv[0].pos) return;
  if (!pv.empty()) f(pv[0].pos);
}

Rejection Grammar::TestPosition(int32_t id) const {
  if (layer_ == 0 || !options_.geometric_rules) return Rejection{};
  const QVec p = VertexOfTokens(pending_block_, id);
  bool linked = false;
  ForEachLinkedPosition([&](const QVec& q) { linked = linked || q == p; });
  if (!linked) return Rejection{};
  return Reject(RejectReason::kZeroLengthEdge, id,
                [&] { return std::string("vertex at the position of a vertex it is linked to"); });
}

// The offset id of position q after block pending_block_ is OffsetTokenOf(q) exactly when
// BlockTokenOf(q) == pending_block_ (the vertex codec is a bijection).
void Grammar::AddPositions(TokenMask* mask) const {
  mask->SetRange(vocab::kOBegin, vocab::kOEnd);
  if (layer_ == 0 || !options_.geometric_rules) return;
  ForEachLinkedPosition([&](const QVec& q) {
    if (BlockTokenOf(q) == pending_block_) mask->Reset(OffsetTokenOf(q));
  });
}

// ---- S: the sizes a window keeps open.
// token_format.md §11.2 (deferred, checked per size): may row b (the current row) carry window w if the
// layer ends with n_size vertices? Wrap-around bits must agree with the partner row's bit
// (both rows cover the pair only when both distances are <= 8), bits at d >= N must be 0,
// layer 1 needs the chain (bit 0 set unless b is last).
bool Grammar::WindowOk(int32_t n_size, int32_t w) const {
  const auto& vs = cur_layer().vertices;
  const int32_t b = static_cast<int32_t>(vs.size()) - 1;
  if (n_size <= b) return false;
  const bool canonical = options_.window_rule == WindowRule::kCanonical;
  if (canonical && layer_ == 1 && !(w & 1) && n_size != b + 1) return false;
  for (int32_t d = std::max(1, n_size - b); d <= kSelfWindow; ++d) {
    const int32_t bit = (w >> (d - 1)) & 1;
    if (d >= n_size) {
      if (bit) return false;
      continue;
    }
    const int32_t a = b + d - n_size, g = n_size - d;
    if (g <= kSelfWindow && canonical && bit != ((vs[a].window >> (g - 1)) & 1)) return false;
    if (bit && options_.geometric_rules && vs[a].pos == vs[b].pos) return false;
  }
  return true;
}

// The layer-1 chain rule for sizes beyond the window (what WindowOk(n, w) reduces to for
// n >= b+9, where no distance wraps around): bit 0 set. Reads w's bit 0 only.
bool Grammar::ChainLets(int32_t w) const {
  return !(options_.window_rule == WindowRule::kCanonical && layer_ == 1 && !(w & 1));
}

// Candidate sizes for the current row's S: still closable, above the row, within the budget
// (the row's K O S already read, at least a B and its due echoes to come).
WindowSizeRule Grammar::WindowRuleNow() const {
  const int32_t b = static_cast<int32_t>(cur_layer().vertices.size()) - 1;
  WindowSizeRule r;
  r.budget_max = BudgetMaxSize(2 + incoming_count_[b]);
  LayerSizeSet cand = sizes_;
  cand.KeepAtLeast(b + 1);
  cand.KeepAtMost(r.budget_max);
  r.far = cand;
  r.far.KeepAtLeast(b + kSelfWindow + 1);
  for (int32_t n = cand.Next(b + 1); n >= 0 && n < b + kSelfWindow + 1; n = cand.Next(n + 1))
    r.near[r.near_count++] = n;
  return r;
}

// {n in the candidates : WindowOk(n, w)}, the far part in bulk. With `any`, stops at the first
// size found: the set may be partial but is empty exactly when the full one is.
LayerSizeSet Grammar::WindowSizes(const WindowSizeRule& rule, int32_t w, bool any) const {
  LayerSizeSet ok;
  if (ChainLets(w)) ok = rule.far;
  for (int32_t i = 0; i < rule.near_count && !(any && !ok.Empty()); ++i)
    if (WindowOk(rule.near[i], w)) ok.Set(rule.near[i]);
  return ok;
}

Rejection Grammar::TestWindow(int32_t id) const {
  const int32_t w = id - vocab::kSBegin;
  const WindowSizeRule rule = WindowRuleNow();
  next_sizes_ = WindowSizes(rule, w);
  if (!next_sizes_.Empty()) return Rejection{};
  if (rule.budget_max < kMaxLayerSize)
    return Reject(RejectReason::kTooLong, id, [&] { return std::string("no room left to finish the layer"); });
  bool beyond_only = true;  // every near size refused w only for bits past its end
  for (int32_t i = 0; i < rule.near_count; ++i)
    if (w < (1 << std::min(kSelfWindow, rule.near[i] - 1))) beyond_only = false;
  return Reject(beyond_only ? RejectReason::kWindowBeyondLayer : RejectReason::kNotCanonical, id, [&] {
    return "window " + std::to_string(w) +
           " fits no layer size still possible (bits past the layer end, disagreement with an "
           "earlier row, the layer-1 chain or a zero-length edge; token_format.md §11.2)";
  });
}

// WindowSizes(rule, w) starts from the far part when ChainLets(w): then it is non-empty as soon
// as the far part is. ChainLets reads w's bit 0 only, so when it passes both values every w is
// admitted; otherwise each w is judged by WindowSizes itself.
void Grammar::AddWindows(TokenMask* mask) const {
  const WindowSizeRule rule = WindowRuleNow();
  const bool far_open = !rule.far.Empty();
  if (far_open && ChainLets(0) && ChainLets(1)) {
    mask->SetRange(vocab::kSBegin, vocab::kSEnd);
    return;
  }
  for (int32_t w = 0; w < kWindowValues; ++w)
    if ((far_open && ChainLets(w)) || !WindowSizes(rule, w, /*any=*/true).Empty()) mask->Set(vocab::kSBegin + w);
}

// ---- X: the values a row may carry at each layer size still open (token_format.md §6, §11.2).
// At size N, for row b: forward statements e <= N-2-b (a pair with a later row, which must echo
// it: the cheapest completion grows by 2), under kUnion free wrap-around statements
// N-1-b <= e (+1), under kCanonical only the next due echo N-1-g (+0); all e <= N-10 (<= 190).
// `future` = FutureRowsCost(b+1, N) when `tight` (see RowFinishCost); not read otherwise.
XRowRule Grammar::XRuleAt(int32_t b, int32_t n, bool tight, int64_t future, int64_t rem) const {
  const int64_t cost = tight ? RowFinishCost(n, future) : 0;
  auto fits = [&](int64_t need) { return !tight || need <= rem; };
  XRowRule r;
  r.hi = std::min(n - kXMargin, kMaxX);
  r.last[XRowRule::kForward] = std::min(r.hi, n - 2 - b);
  r.fits[XRowRule::kForward] = fits(cost + 2);
  if (options_.window_rule == WindowRule::kUnion) {
    r.first[XRowRule::kWrap] = n - 1 - b;
    r.last[XRowRule::kWrap] = r.hi;
    r.fits[XRowRule::kWrap] = fits(cost + 1);
  } else if (matched_[n] < g_count_) {
    const int32_t echo = n - 1 - g_desc_[matched_[n]];
    r.first[XRowRule::kEcho] = echo;
    r.last[XRowRule::kEcho] = std::min(echo, r.hi);
    r.fits[XRowRule::kEcho] = fits(cost);
  }
  return r;
}

// Calls f(N, XRuleAt(b, N, ...)) for every size N the row still allows, in increasing order.
template <class F>
void Grammar::ForEachXRule(F&& f) const {
  const int32_t b = static_cast<int32_t>(cur_layer().vertices.size()) - 1;
  const bool tight = !FarFromCap();
  const int64_t rem = remaining();
  int64_t future = 0;
  int32_t row = b + 1;
  for (int32_t n = row_sizes_.Next(0); n >= 0; n = row_sizes_.Next(n + 1)) {
    if (tight)
      for (; row < n; ++row) future += 4 + incoming_count_[row];
    f(n, XRuleAt(b, n, tight, future, rem));
  }
}

// Writes the sizes the value keeps open to next_sizes_ for ApplyX.
Rejection Grammar::TestX(int32_t id) const {
  const int32_t e = id - vocab::kXBegin;
  if (e <= last_x_)
    return Reject(RejectReason::kXNotIncreasing, id,
                  [&] { return std::string("X values must increase within a vertex (token_format.md §11.2)"); });
  if (e < kMinX || e > kMaxX)
    return Reject(RejectReason::kXOutOfRange, id, [&] {
      return std::string("X value " + std::to_string(e) + " outside [8, 190] (token_format.md §6)");
    });
  LayerSizeSet& ok = next_sizes_;
  ok.Clear();
  bool range_only = true, budget_hit = false;
  ForEachXRule([&](int32_t n, const XRowRule& rule) {
    range_only = range_only && e > rule.hi;
    if (rule.Admits(e))
      ok.Set(n);
    else if (rule.Covers(e))
      budget_hit = true;
  });
  if (!ok.Empty()) return Rejection{};
  if (budget_hit)
    return Reject(RejectReason::kTooLong, id, [&] { return std::string("no room left to finish the layer"); });
  return Reject(range_only ? RejectReason::kXOutOfRange : RejectReason::kNotCanonical, id, [&] {
    return "X value " + std::to_string(e) +
           " fits no layer size still possible (needs N >= e+10 and agreement with earlier rows; token_format.md "
           "§11.2)";
  });
}

// The values TestX admits: above the last one and >= 8, inside a fitting interval of some size.
// Far from the cap every interval fits; with no echo due (or under kUnion) a size's intervals
// join to [0, min(N-10, N-2-b)] (kUnion: [0, min(N-10, 190)]), which grows with N, so the
// largest size's rule covers all the others.
void Grammar::AddX(TokenMask* mask) const {
  const int32_t lo = std::max(last_x_ + 1, kMinX);
  auto add = [&](int32_t, const XRowRule& rule) {
    for (int k = 0; k < XRowRule::kKinds; ++k) {
      const int32_t first = std::max(lo, rule.first[k]);
      if (rule.fits[k] && first <= rule.last[k])
        mask->SetRange(vocab::kXBegin + first, vocab::kXBegin + rule.last[k] + 1);
    }
  };
  const bool canonical = options_.window_rule == WindowRule::kCanonical;
  if (FarFromCap() && (g_count_ == 0 || !canonical)) {
    const int32_t n = row_sizes_.Max();
    if (n >= 0) add(n, XRuleAt(static_cast<int32_t>(cur_layer().vertices.size()) - 1, n, false, 0, 0));
    return;
  }
  ForEachXRule(add);
}

// ---- B: the cases a B token may take at each start column (token_format.md §7.3, §11.3).
namespace {
// Bit c set iff case c's last 1 lies within `room` columns: ℓ(c) <= room.
uint32_t CasesEndingWithin(int32_t room) {
  static const auto table = [] {
    std::array<uint32_t, kBetweenWindow + 1> t{};
    for (int32_t r = 0; r <= kBetweenWindow; ++r)
      for (int32_t c = 0; c < kBetweenCases; ++c)
        if (BetweenCaseLastOne(c) <= r) t[r] |= uint32_t{1} << c;
    return t;
  }();
  return table[std::min(room, kBetweenWindow)];
}
constexpr uint32_t kAllCases = (uint32_t{1} << kBetweenCases) - 1;
}  // namespace

// Smallest start column: 0 for the row's first B, the §7.3 continuation minimum after a B.
int32_t Grammar::BMinStart() const {
  return phase_ == GrammarPhase::kAfterB ? BetweenNextMinStart(last_s_, last_c_) : 0;
}

// Cases at start column s: the segment ends inside the previous layer (s + ℓ(c) <= N_prev - 1)
// and, with geometric rules, points at no column at the current vertex's position.
uint32_t Grammar::BCasesAt(int32_t s) const {
  const int32_t room = n_prev_ - 1 - s;
  if (room < 0) return 0;
  uint32_t cases = CasesEndingWithin(room);
  if (options_.geometric_rules && eq_cols_any_)
    for (int32_t c = 0; c < kBetweenCases; ++c)
      if (((cases >> c) & 1) && !ColumnsClear(s, c)) cases &= ~(uint32_t{1} << c);
  return cases;
}

bool Grammar::ColumnsClear(int32_t s, int32_t c) const {
  if (!eq_cols_any_) return true;
  if (eq_cols_.Test(s)) return false;
  const int32_t pat = BetweenCasePattern(c);
  for (int32_t p = 1; p <= kBetweenWindow; ++p)
    if (((pat >> (p - 1)) & 1) && eq_cols_.Test(s + p)) return false;
  return true;
}

Rejection Grammar::TestB(int32_t id) const {
  const int32_t r = id - vocab::kBBegin, s = r / kBetweenCases, c = r % kBetweenCases;
  const int32_t min_s = BMinStart();
  if (s < min_s)
    return Reject(RejectReason::kBContinuation, id, [&] {
      return std::string("B start " + std::to_string(s) + " below the continuation minimum " + std::to_string(min_s) +
                         " (token_format.md §7.3)");
    });
  if ((BCasesAt(s) >> c) & 1) return Rejection{};
  if (s + BetweenCaseLastOne(c) > n_prev_ - 1)
    return Reject(RejectReason::kBOutsidePrevLayer, id, [&] {
      return std::string("segment ends at column " + std::to_string(s + BetweenCaseLastOne(c)) +
                         " but the previous layer has " + std::to_string(n_prev_) +
                         " vertices (token_format.md §11.3)");
    });
  return Reject(RejectReason::kZeroLengthEdge, id,
                [&] { return std::string("B segment links two vertices at one position"); });
}

// BCasesAt(s) is every case while room >= kBetweenWindow and no column is excluded: those starts
// form one id range; the last kBetweenWindow starts (or all, with excluded columns) per column.
void Grammar::AddB(TokenMask* mask) const {
  const int32_t last = n_prev_ - 1;
  int32_t s = BMinStart();
  if (!(options_.geometric_rules && eq_cols_any_) && CasesEndingWithin(kBetweenWindow) == kAllCases) {
    const int32_t full_hi = last - kBetweenWindow;
    if (s <= full_hi) {
      mask->SetRange(vocab::kBBegin + kBetweenCases * s, vocab::kBBegin + kBetweenCases * (full_hi + 1));
      s = full_hi + 1;
    }
  }
  for (; s <= last; ++s)
    for (uint32_t m = BCasesAt(s); m; m &= m - 1) mask->Set(vocab::kBBegin + kBetweenCases * s + __builtin_ctz(m));
}

}  // namespace silk
