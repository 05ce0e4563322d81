// SPDX-License-Identifier: MIT
// The grammar state machine (token_format.md §11): its state, Step (the one driver of Accept and Check
// over the rule table of grammar_rules.cpp) and what each admitted token does to the state.
// Rule comments name the spec section they implement; see grammar.h for the guarantees.
#include "decoder/grammar.h"
#include "decoder/grammar_limits.h"

#include <climits>
#include <string>

#include "tokenizer/adjacency/between_layer_cases.h"
#include "tokenizer/packing/vertex_codec.h"
#include "tokenizer/vocabulary_layout.h"

namespace silk {

using namespace grammar_limits;  // NOLINT: the grammar's own constants

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
  // token_format.md §11.2: layer 1 needs N >= 2 (the root has >= 2 neighbours); every layer N <= 200.
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

Rejection Grammar::Check(int32_t id, bool with_message) const {
  // Step with commit = false reads the state only: the table's tests and gates are const (they
  // write only the scratch next_sizes_), the Apply functions run only when committing.
  // `messages_` only decides whether a refusal's text is built.
  Grammar* self = const_cast<Grammar*>(this);
  self->messages_ = with_message;
  Rejection r = self->Step(id, false);
  self->messages_ = true;
  return r;
}

// Every token is judged by the rule table alone: the checks that hold in every phase (a model
// id, nothing after EOS, no PAD, the length cap), then the row of the current phase
// (grammar_rules.cpp). With commit = false nothing is written; with commit = true the admitted
// id joins the history and its class's Apply updates the state.
Rejection Grammar::Step(int32_t id, bool commit) {
  if (id < 0 || id >= vocab::k_model_vocab_size)
    return Reject(RejectReason::kOutOfVocabulary, id, [&] { return std::string("id outside 0..10268"); });
  if (Rejection r = NotEnded(id); !r.ok()) return r;
  if (id == vocab::k_pad_id)
    return Reject(RejectReason::kPadToken, id,
                  [&] { return std::string("PAD is padding, never a sequence token (token_format.md §9)"); });
  if (Rejection r = RoomForToken(id); !r.ok()) return r;
  const GrammarPhaseRule& row = RuleRow(phase_);
  const GrammarClassRule* cls = row.Find(id);
  if (!cls && id == vocab::k_eos_id)
    return Reject(RejectReason::kEosNotAfterE, id,
                  [&] { return std::string("EOS only directly after the E of a component (token_format.md §11.4)"); });
  if (!cls)
    return Reject(RejectReason::kWrongClass, id,
                  [&] { return std::string("expected ") + row.expects + " (token_format.md §11.1)"; });
  if (cls->test)
    if (Rejection r = (this->*cls->test)(id); !r.ok()) return r;
  for (GrammarGate gate : cls->gates) {
    if (!gate) break;
    if (Rejection r = (this->*gate)(id); !r.ok()) return r;
  }
  if (!commit) return Rejection{};
  history_.push_back(id);
  (this->*cls->apply)(id);
  mask_valid_ = false;
  return Rejection{};
}

Rejection Grammar::Accept(int32_t id) { return Step(id, true); }

// What each admitted token does. Every one runs after Step pushed the id on the history.

void Grammar::ApplyEos(int32_t) { phase_ = GrammarPhase::kEnded; }

void Grammar::ApplyComponentStart(int32_t) {
  stream_.components.emplace_back();
  stream_.components.back().layers.emplace_back();
  layer_ = 0;
  n_prev_ = 0;
  closed_layers_ = 0;
  phase_ = GrammarPhase::kWantK;
  StartLayer();
}

void Grammar::ApplyBlock(int32_t id) {
  cur_layer().vertices.emplace_back();
  pending_block_ = id;
  phase_ = GrammarPhase::kWantO;
}

void Grammar::ApplyOffset(int32_t id) {
  const QVec p = VertexOfTokens(pending_block_, id);
  cur_layer().vertices.back().pos = p;
  if (layer_ == 0) {
    phase_ = GrammarPhase::kWantU0;
    return;
  }
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

void Grammar::ApplyRootLayerEnd(int32_t) {
  CloseLayer();
  n_prev_ = 1;
  layer_ = 1;
  stream_.components.back().layers.emplace_back();
  phase_ = GrammarPhase::kWantK;
  StartLayer();
}

// S: the row's sizes are the ones TestWindow left open; the row's due echoes (§6, pairs stated
// from both sides) are listed from the farthest earlier row down.
void Grammar::ApplyWindow(int32_t id) {
  const int32_t b = static_cast<int32_t>(cur_layer().vertices.size()) - 1;
  cur_layer().vertices.back().window = id - vocab::kSBegin;
  row_sizes_ = next_sizes_;
  g_count_ = 0;
  for (int32_t gg = incoming_[b].Max(); gg >= 0; gg = incoming_[b].Prev(gg - 1))
    g_desc_[g_count_++] = static_cast<uint8_t>(gg);
  matched_.fill(0);
  last_x_ = -1;
  phase_ = GrammarPhase::kAfterS;
}

// X: at each size it stays open at, a wrap-around value is the next echo; a forward value is
// one more echo the target row owes.
void Grammar::ApplyX(int32_t id) {
  const int32_t e = id - vocab::kXBegin;
  const int32_t b = static_cast<int32_t>(cur_layer().vertices.size()) - 1;
  cur_layer().vertices.back().extras.push_back(e);
  for (int32_t n = next_sizes_.Next(0); n >= 0; n = next_sizes_.Next(n + 1))
    if (e >= n - 1 - b) ++matched_[n];
  row_sizes_ = next_sizes_;
  last_x_ = e;
  const int32_t target = b + e + 1;  // forward partner if the layer is longer than target
  if (target < kMaxLayerSize && !incoming_[target].Test(e + 1)) {
    incoming_[target].Set(e + 1);
    ++incoming_count_[target];
    ++incoming_total_;
  }
}

void Grammar::ApplyFirstB(int32_t id) {
  sizes_ = next_sizes_;  // the sizes RowCanFinish found for the finished row
  ApplyNextB(id);
  phase_ = GrammarPhase::kAfterB;
}

void Grammar::ApplyNextB(int32_t id) {
  const int32_t r = id - vocab::kBBegin, s = r / kBetweenCases, c = r % kBetweenCases;
  cur_layer().vertices.back().between.push_back(BetweenToken{s, c});
  last_s_ = s;
  last_c_ = c;
}

// U or E: the layer closes at its current size; U opens the next layer of the component.
void Grammar::ApplyLayerEnd(int32_t id) {
  const int32_t n = static_cast<int32_t>(cur_layer().vertices.size());
  CloseLayer();
  if (id != vocab::kUBegin) {
    phase_ = GrammarPhase::kAfterE;
    return;
  }
  n_prev_ = n;
  ++layer_;
  stream_.components.back().layers.emplace_back();
  phase_ = GrammarPhase::kWantK;
  StartLayer();
}

}  // namespace silk
