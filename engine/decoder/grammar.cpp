// The grammar state machine (spec §11): acceptance, legal masks, rewind. Rule comments name
// the spec section they implement; see grammar.h for the list and the guarantees.
#include "decoder/grammar.h"
#include "decoder/grammar_limits.h"

#include <algorithm>
#include <climits>
#include <cstring>
#include <string>

#include "tokenizer/between_layer_cases.h"
#include "tokenizer/vertex_codec.h"
#include "tokenizer/vocabulary_layout.h"

namespace silk {
namespace {

using namespace grammar_limits;  // NOLINT: the grammar's own constants

enum class Kind { kC, kU, kE, kX, kS, kB, kK, kO, kEos, kPad, kBad };

Kind KindOf(int32_t id) {
  if (id < 0 || id >= vocab::k_model_vocab_size) return Kind::kBad;
  if (id == vocab::kCBegin) return Kind::kC;
  if (id == vocab::kUBegin) return Kind::kU;
  if (id == vocab::kEBegin) return Kind::kE;
  if (id < vocab::kXEnd) return Kind::kX;
  if (id < vocab::kSEnd) return Kind::kS;
  if (id < vocab::kBEnd) return Kind::kB;
  if (id < vocab::kKEnd) return Kind::kK;
  if (id < vocab::kOEnd) return Kind::kO;
  if (id == vocab::k_eos_id) return Kind::kEos;
  return Kind::kPad;
}

const char* PhaseExpects(GrammarPhase p) {
  switch (p) {
    case GrammarPhase::kStart: return "C";
    case GrammarPhase::kWantK: return "K (block)";
    case GrammarPhase::kWantO: return "O (offset)";
    case GrammarPhase::kWantU0: return "U (layer 0 holds only the root)";
    case GrammarPhase::kWantS: return "S (window)";
    case GrammarPhase::kAfterS: return "X or B";
    case GrammarPhase::kAfterB: return "B, K, U or E";
    case GrammarPhase::kAfterE: return "C or EOS";
    case GrammarPhase::kEnded: return "nothing (after EOS)";
  }
  return "?";
}

}  // namespace

Grammar::Grammar(GrammarOptions options) : options_(options) { Reset(); }

void Grammar::Reset() {
  phase_ = GrammarPhase::kStart;
  history_.clear();
  checkpoints_.clear();
  stream_.components.clear();
  findings_.clear();
  layer_ = n_prev_ = closed_layers_ = 0;
  vertices_total_ = 0;
  mask_valid_ = false;
}

int32_t Grammar::remaining() const {
  if (options_.max_length <= 0) return INT_MAX / 4;
  return options_.max_length - static_cast<int32_t>(history_.size());
}

Rejection Grammar::MakeRejection(RejectReason r, int32_t id, const std::string& why) const {
  return Rejection{r, "token " + std::to_string(history_.size()) + " (id " + std::to_string(id) + "): " + why};
}

void Grammar::ResetLayerState() {
  // Spec §11.2: layer 1 needs N >= 2 (the root has >= 2 neighbours); every layer N <= 200.
  sizes_.Fill(layer_ == 1 ? 2 : 1, kMaxLayerSize);
  for (auto& s : incoming_) s.Clear();
  incoming_count_.fill(0);
  incoming_total_ = 0;
}

void Grammar::StartLayer() {
  ResetLayerState();
  checkpoints_.push_back(Checkpoint{history_.size(), phase_, layer_, n_prev_, closed_layers_, vertices_total_,
                                    stream_.components.size(), findings_.size()});
}

// Tokens needed by rows from_row..n_size-1 if each is K O S B plus its required X values.
int64_t Grammar::FutureRowsCost(int32_t from_row, int32_t n_size) const {
  int64_t c = 0;
  for (int32_t r = std::max(from_row, 0); r < n_size; ++r) c += 4 + incoming_count_[r];
  return c;
}

// Spec §11.2 (deferred, checked per size): may row b (the current row) carry window w if the
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

Rejection Grammar::CheckBSegment(int32_t id, int32_t s, int32_t c) const {
  if (s + BetweenCaseLastOne(c) > n_prev_ - 1)
    return Reject(RejectReason::kBOutsidePrevLayer, id,
        [&] { return std::string("segment ends at column " + std::to_string(s + BetweenCaseLastOne(c)) +
                      " but the previous layer has " + std::to_string(n_prev_) + " vertices (spec §11.3)"); });
  if (options_.geometric_rules && !ColumnsClear(s, c))
    return Reject(RejectReason::kZeroLengthEdge, id,
        [&] { return std::string("B segment links two vertices at one position"); });
  return Rejection{};
}

bool Grammar::ColumnsClear(int32_t s, int32_t c) const {
  if (!eq_cols_any_) return true;
  if (eq_cols_.Test(s)) return false;
  const int32_t pat = BetweenCasePattern(c);
  for (int32_t p = 1; p <= kBetweenWindow; ++p)
    if (((pat >> (p - 1)) & 1) && eq_cols_.Test(s + p)) return false;
  return true;
}

Rejection Grammar::Check(int32_t id, bool with_message) const {
  // Step with commit = false reads the state only (every branch returns before its first write);
  // `messages_` only decides whether a refusal's text is built.
  Grammar* self = const_cast<Grammar*>(this);
  self->messages_ = with_message;
  Rejection r = self->Step(id, false);
  self->messages_ = true;
  return r;
}

// One place for every acceptance rule: with commit = false it only answers, with commit = true
// it also applies the token. Each branch checks first and writes only after
// `if (!commit) return Rejection{};`.
Rejection Grammar::Step(int32_t id, bool commit) {
  const Kind k = KindOf(id);
  if (k == Kind::kBad) return Reject(RejectReason::kOutOfVocabulary, id,
      [&] { return std::string("id outside 0..10268"); });
  if (phase_ == GrammarPhase::kEnded) return Reject(RejectReason::kAfterEos, id,
      [&] { return std::string("nothing may follow EOS"); });
  if (k == Kind::kPad) return Reject(RejectReason::kPadToken, id,
      [&] { return std::string("PAD is padding, never a sequence token (spec §9)"); });
  // Spec §9: at most max_length tokens including EOS.
  if (options_.max_length > 0 && static_cast<int64_t>(history_.size()) + 1 > options_.max_length)
    return Reject(RejectReason::kTooLong, id, [&] { return std::string("sequence longer than the length limit"); });
  if (k == Kind::kEos && phase_ != GrammarPhase::kAfterE)
    return Reject(RejectReason::kEosNotAfterE, id,
        [&] { return std::string("EOS only directly after the E of a component (spec §11.4)"); });

  auto wrong = [&]() {
    return Reject(RejectReason::kWrongClass, id,
        [&] { return std::string(std::string("expected ") + PhaseExpects(phase_) + " (spec §11.1)"); });
  };
  const int32_t rem_after = remaining() - 1;

  switch (phase_) {
    case GrammarPhase::kStart:
    case GrammarPhase::kAfterE: {
      if (k == Kind::kEos) {
        if (!commit) return Rejection{};
        history_.push_back(id);
        phase_ = GrammarPhase::kEnded;
        break;
      }
      if (k != Kind::kC) return wrong();
      if (rem_after < kMinComponentTokens)  // C + the smallest component + EOS must fit
        return Reject(RejectReason::kTooLong, id, [&] { return std::string("no room left for a whole component"); });
      if (!commit) return Rejection{};
      history_.push_back(id);
      stream_.components.emplace_back();
      stream_.components.back().layers.emplace_back();
      layer_ = 0;
      n_prev_ = 0;
      closed_layers_ = 0;
      phase_ = GrammarPhase::kWantK;
      StartLayer();
      break;
    }
    case GrammarPhase::kWantK:
    case GrammarPhase::kAfterB: {
      if (phase_ == GrammarPhase::kAfterB && k == Kind::kB) {
        // Spec §7.3 / §11.3: continuation start >= s' + ℓ(c') + 2 (truncating) or s' + 6.
        const int32_t r = id - vocab::kBBegin, s = r / kBetweenCases, c = r % kBetweenCases;
        if (s < BetweenNextMinStart(last_s_, last_c_))
          return Reject(RejectReason::kBContinuation, id,
              [&] { return std::string("B start " + std::to_string(s) + " below the continuation minimum " +
                            std::to_string(BetweenNextMinStart(last_s_, last_c_)) + " (spec §7.3)"); });
        if (Rejection bad = CheckBSegment(id, s, c); !bad.ok()) return bad;
        const int32_t n = static_cast<int32_t>(cur_layer().vertices.size());
        if (!FarFromCap() && rem_after < FutureRowsCost(n, std::max(n, sizes_.Next(n))) + 2)
          return Reject(RejectReason::kTooLong, id, [&] { return std::string("no room left to close the layer"); });
        if (!commit) return Rejection{};
        history_.push_back(id);
        cur_layer().vertices.back().between.push_back(BetweenToken{s, c});
        last_s_ = s;
        last_c_ = c;
        break;
      }
      if (phase_ == GrammarPhase::kAfterB && (k == Kind::kU || k == Kind::kE)) {
        const int32_t n = static_cast<int32_t>(cur_layer().vertices.size());
        if (!sizes_.Test(n))
          return Reject(RejectReason::kLayerNotClosable, id, [&] { return std::string("layer of " + std::to_string(n) +
                        " vertices cannot close: " + ExplainClose(n)); });
        if (k == Kind::kU) {
          if (layer_ >= kMaxLayerIndex)
            return Reject(RejectReason::kTooManyLayers, id,
                [&] { return std::string("layer index 200 would follow (spec §5.3)"); });
          if (rem_after < 4 + 1 + 1)
            return Reject(RejectReason::kTooLong, id, [&] { return std::string("no room for another layer"); });
        }
        if (!commit) return Rejection{};
        history_.push_back(id);
        CloseLayer();
        if (k == Kind::kU) {
          n_prev_ = n;
          ++layer_;
          stream_.components.back().layers.emplace_back();
          phase_ = GrammarPhase::kWantK;
          StartLayer();
        } else {
          phase_ = GrammarPhase::kAfterE;
        }
        break;
      }
      if (k != Kind::kK) return wrong();
      const int32_t n = static_cast<int32_t>(cur_layer().vertices.size());
      if (phase_ == GrammarPhase::kAfterB) {
        if (n >= kMaxLayerSize)
          return Reject(RejectReason::kLayerTooLarge, id,
              [&] { return std::string("a layer holds at most 200 vertices (spec §1.3)"); });
        const int32_t next = sizes_.Next(n + 1);
        if (next < 0 && !FarFromCap())
          return Reject(RejectReason::kTooLong, id,
              [&] { return std::string("no room left for another vertex and the layer's end"); });
        if (next < 0)
          return Reject(RejectReason::kNotCanonical, id,
              [&] { return "the earlier rows of this layer only fit a layer of " + std::to_string(n) + " vertices"; });
        if (rem_after + 1 < FutureRowsCost(n, next) + 2)
          return Reject(RejectReason::kTooLong, id,
              [&] { return std::string("no room left for another vertex and the layer's end"); });
      }
      if (!commit) return Rejection{};
      history_.push_back(id);
      cur_layer().vertices.emplace_back();
      pending_block_ = id;
      phase_ = GrammarPhase::kWantO;
      break;
    }
    case GrammarPhase::kWantO: {
      if (k != Kind::kO) return wrong();
      const QVec p = VertexOfTokens(pending_block_, id);
      if (layer_ > 0 && options_.geometric_rules && PositionForbidden(p))
        return Reject(RejectReason::kZeroLengthEdge, id,
            [&] { return std::string("vertex at the position of a vertex it is linked to"); });
      if (!commit) return Rejection{};
      history_.push_back(id);
      auto& v = cur_layer().vertices.back();
      v.pos = p;
      if (layer_ == 0) {
        phase_ = GrammarPhase::kWantU0;
      } else {
        // Previous-layer columns at this position (usually none): B may not point at them.
        eq_cols_.Clear();
        eq_cols_any_ = false;
        if (options_.geometric_rules) {
          const auto& pv = prev_layer().vertices;
          for (int32_t j = 0; j < n_prev_; ++j)
            if (pv[j].pos == p) {
              eq_cols_.Set(j);
              eq_cols_any_ = true;
            }
        }
        phase_ = GrammarPhase::kWantS;
      }
      break;
    }
    case GrammarPhase::kWantU0: {
      if (k == Kind::kE) return Reject(RejectReason::kLayerZeroSize, id,
          [&] { return std::string("E directly after the root: a component needs layer 1 (spec §8.3)"); });
      if (k != Kind::kU) return wrong();
      if (!commit) return Rejection{};
      history_.push_back(id);
      CloseLayer();
      n_prev_ = 1;
      layer_ = 1;
      stream_.components.back().layers.emplace_back();
      phase_ = GrammarPhase::kWantK;
      StartLayer();
      break;
    }
    case GrammarPhase::kWantS: {
      if (k != Kind::kS) return wrong();
      const int32_t w = id - vocab::kSBegin;
      const int32_t b = static_cast<int32_t>(cur_layer().vertices.size()) - 1;
      const int32_t g = incoming_count_[b];
      LayerSizeSet cand = sizes_;
      cand.KeepAtLeast(b + 1);
      const int32_t budget_max = BudgetMaxSize(2 + g);
      LayerSizeSet ok;
      bool beyond_only = true;
      cand.KeepAtMost(budget_max);
      // Sizes >= b+9: no wrap-around bits, only the layer-1 chain rule applies (bulk).
      if (!(options_.window_rule == WindowRule::kCanonical && layer_ == 1 && !(w & 1))) {
        ok = cand;
        ok.KeepAtLeast(b + kSelfWindow + 1);
      }
      for (int32_t n = cand.Next(b + 1); n >= 0 && n < b + kSelfWindow + 1; n = cand.Next(n + 1)) {
        if (WindowOk(n, w)) ok.Set(n);
        else if (w < (1 << std::min(kSelfWindow, n - 1))) beyond_only = false;
      }
      if (ok.Empty()) {
        if (budget_max < kMaxLayerSize) return Reject(RejectReason::kTooLong, id,
            [&] { return std::string("no room left to finish the layer"); });
        return Reject(beyond_only ? RejectReason::kWindowBeyondLayer : RejectReason::kNotCanonical, id, [&] {
          return "window " + std::to_string(w) +
                 " fits no layer size still possible (bits past the layer end, disagreement with an "
                 "earlier row, the layer-1 chain or a zero-length edge; spec §11.2)";
        });
      }
      if (!commit) return Rejection{};
      history_.push_back(id);
      cur_layer().vertices.back().window = w;
      row_sizes_ = ok;
      g_count_ = 0;
      for (int32_t gg = incoming_[b].Max(); gg >= 0; gg = incoming_[b].Prev(gg - 1))
        g_desc_[g_count_++] = static_cast<uint8_t>(gg);
      matched_.fill(0);
      last_x_ = -1;
      phase_ = GrammarPhase::kAfterS;
      break;
    }
    case GrammarPhase::kAfterS: {
      const int32_t b = static_cast<int32_t>(cur_layer().vertices.size()) - 1;
      const bool canonical = options_.window_rule == WindowRule::kCanonical;
      if (k == Kind::kX) {
        const int32_t e = id - vocab::kXBegin;
        if (e <= last_x_)
          return Reject(RejectReason::kXNotIncreasing, id,
              [&] { return std::string("X values must increase within a vertex (spec §11.2)"); });
        if (e < kMinX || e > kMaxX)
          return Reject(RejectReason::kXOutOfRange, id,
              [&] { return std::string("X value " + std::to_string(e) + " outside [8, 190] (spec §6)"); });
        const int32_t target = b + e + 1;  // forward partner if the layer is longer than target
        // Length budget, exact (see RowFinishCost): a forward X adds one echo to a later row,
        // an echo removes one from this row, a free wrap-around X (kUnion) changes nothing.
        const bool tight = !FarFromCap();
        const int64_t rem = remaining();
        LayerSizeSet ok;
        bool range_only = true, budget_hit = false;
        int64_t future = 0;
        int32_t row = b + 1;
        for (int32_t n = row_sizes_.Next(0); n >= 0; n = row_sizes_.Next(n + 1)) {
          if (e > n - kXMargin) continue;  // §6: X values <= N-10
          range_only = false;
          if (tight)
            for (; row < n; ++row) future += 4 + incoming_count_[row];
          const int64_t cost = tight ? RowFinishCost(n, future) : 0;
          int64_t need = -1;
          if (e < n - 1 - b) {
            need = cost + 2;  // forward statement to a later row: free now, that row must echo it
          } else if (!canonical) {
            need = cost + 1;
          } else if (matched_[n] < g_count_ && e == n - 1 - g_desc_[matched_[n]]) {
            need = cost;  // wrap-around statement echoing an earlier row's forward X (§6 twice-emitted pairs)
          }
          if (need < 0) continue;
          if (tight && need > rem) {
            budget_hit = true;
            continue;
          }
          ok.Set(n);
        }
        if (ok.Empty() && budget_hit)
          return Reject(RejectReason::kTooLong, id, [&] { return std::string("no room left to finish the layer"); });
        if (ok.Empty())
          return Reject(range_only ? RejectReason::kXOutOfRange : RejectReason::kNotCanonical, id, [&] {
            return "X value " + std::to_string(e) +
                   " fits no layer size still possible (needs N >= e+10 and agreement with earlier rows; spec §11.2)";
          });
        if (!commit) return Rejection{};
        history_.push_back(id);
        cur_layer().vertices.back().extras.push_back(e);
        for (int32_t n = ok.Next(0); n >= 0; n = ok.Next(n + 1))
          if (e >= n - 1 - b) ++matched_[n];
        row_sizes_ = ok;
        last_x_ = e;
        if (target < kMaxLayerSize) {
          if (!incoming_[target].Test(e + 1)) {
            incoming_[target].Set(e + 1);
            ++incoming_count_[target];
            ++incoming_total_;
          }
        }
        break;
      }
      if (k != Kind::kB) return wrong();
      const int32_t r = id - vocab::kBBegin, s = r / kBetweenCases, c = r % kBetweenCases;
      if (Rejection bad = CheckBSegment(id, s, c); !bad.ok()) return bad;
      LayerSizeSet fin;
      const int32_t budget_max = BudgetMaxSize(1);
      if (!canonical || g_count_ == 0) {
        fin = row_sizes_;
        fin.KeepAtMost(budget_max);
      } else {
        for (int32_t n = row_sizes_.Next(0); n >= 0 && n <= budget_max; n = row_sizes_.Next(n + 1))
          if (matched_[n] == g_count_) fin.Set(n);
      }
      if (fin.Empty() && budget_max < kMaxLayerSize)
        return Reject(RejectReason::kTooLong, id, [&] { return std::string("no room left to finish the layer"); });
      if (fin.Empty())
        return Reject(RejectReason::kNotCanonical, id,
            [&] {
              return std::string(
                  "the vertex's X values miss a pair an earlier row states (spec §11.2 canonical consistency)");
            });
      if (!commit) return Rejection{};
      history_.push_back(id);
      sizes_ = fin;
      cur_layer().vertices.back().between.push_back(BetweenToken{s, c});
      last_s_ = s;
      last_c_ = c;
      phase_ = GrammarPhase::kAfterB;
      break;
    }
    case GrammarPhase::kEnded:
      return wrong();
  }
  mask_valid_ = false;
  return Rejection{};
}

Rejection Grammar::Accept(int32_t id) { return Step(id, true); }

}  // namespace silk
