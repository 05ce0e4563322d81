// SPDX-License-Identifier: MIT
// Grammar: the state machine of legal Mesh Silksong sequences over the full model vocabulary
// (token_format.md §9, §11), for constrained sampling and for checking streams token by token.
//
// Rules enforced (the rule table, grammar_rules.h/.cpp: each phase written once, as the id
// classes it takes and their predicates, documented at their code in grammar_gates.cpp and
// grammar_predicates.cpp; Accept, Check and the legal mask all read that table):
//  * token kinds in packing order (C, root K O, U, then K O S X* B+ per vertex, U/E), EOS only
//    after an E, PAD never;
//  * S bits only at distances < N, X values strictly increasing in [8, N-10] (so only N>=18),
//    B segments inside the previous layer with the §7.3 continuation minimum (layer 1: only 460);
//  * canonical consistency of the self-layer rows (§11.2) and the layer-1 chain rule, kept as
//    the set of layer sizes N at which the layer could still be closed: a token is accepted
//    only if that set stays non-empty, U/E only when the current size is in it;
//  * layer size <= 200, layer index <= 199, total length <= max_length (EOS included);
//  * geometric rule: no edge joins two vertices at the same grid position (holds for all 154
//    official streams; positions themselves DO repeat inside components, token_format.md §3.6).
// Liveness: every accepted prefix can be completed to a legal sequence within max_length (the
// legal mask is never empty before EOS). Near the cap each token is admitted only if the exact
// cheapest completion after it (finish the row, close at the cheapest size, E, EOS; see
// RowFinishCost/BudgetMaxSize) still fits, and that completion only uses admitted tokens.
// Guarantee (tested): every accepted sequence decodes (BuildMesh) to a mesh whose every edge
// has at most 2 faces, consistently oriented, no face with two corners at one position, and
// exactly one mesh component per C token with vertices.
#pragma once
#include <array>
#include <cstdint>
#include <vector>

#include "core/status.h"
#include "decoder/grammar_rejection.h"
#include "decoder/grammar_rules.h"
#include "decoder/layer_size_set.h"
#include "decoder/token_mask.h"
#include "tokenizer/layering/layered_stream.h"

namespace silk {

// How self-layer rows that state a pair differently are treated (token_format.md §11.2).
enum class WindowRule : int32_t {
  kCanonical = 0,  // the encoder's rule: refuse (mask) until consistent
  kUnion = 1,      // the official decoder's rule: accept, the pair is an edge if either row says
                   // so; each disagreement is recorded as a finding (repair of a likely false 0)
};

struct GrammarOptions {
  int32_t max_length = 10240;  // tokens incl. EOS (token_format.md §9); 0 = unlimited (long corpus streams)
  WindowRule window_rule = WindowRule::kCanonical;
  bool geometric_rules = true;  // zero-length edges refused
};

// A disagreement of two rows about one in-layer pair, under WindowRule::kUnion.
struct WindowFinding {
  int32_t component = 0, layer = 0, row_a = 0, row_b = 0;  // the pair; a < b, layer-local
};

enum class GrammarPhase : uint8_t { kStart, kWantK, kWantO, kWantU0, kWantS, kAfterS, kAfterB, kAfterE, kEnded };

class Grammar {
 public:
  explicit Grammar(GrammarOptions options = {});

  void Reset();
  // Accepts one id (0..10268). On rejection the state is unchanged.
  Rejection Accept(int32_t id);
  // What Accept(id) would answer now, without changing anything (same code path: Step over the
  // rule table of grammar_rules.h, which the legal mask reads too).
  // with_message = false skips building the refusal's text (the verdict is the same).
  Rejection Check(int32_t id, bool with_message = true) const;
  // The ids Accept would take now. Cached until the next Accept/Reset/Rewind.
  const TokenMask& LegalMask();
  // The only legal id, or -1.
  int32_t Forced();
  bool CanEnd() const { return phase_ == GrammarPhase::kAfterE; }
  bool Ended() const { return phase_ == GrammarPhase::kEnded; }
  Grammar Clone() const { return *this; }
  // Back to the state after the first `prefix` accepted tokens (replays from the last layer
  // start). Error if prefix > size().
  Status Rewind(size_t prefix);

  // Smallest layer size >= from at which the current layer could still close, -1 if none
  // (for samplers that aim at a layer size; meaningful inside a layer of index >= 1).
  int32_t NextClosableSize(int32_t from) const;
  // In state kWantS: would window w keep layer size n_size possible? (sampler aid)
  bool WindowFits(int32_t n_size, int32_t w) const {
    return phase_ == GrammarPhase::kWantS && sizes_.Test(n_size) && WindowOk(n_size, w);
  }

  size_t size() const { return history_.size(); }
  const std::vector<int32_t>& tokens() const { return history_; }
  GrammarPhase phase() const { return phase_; }
  // Components/layers/vertices read so far (the current layer is the last, possibly open).
  const LayeredStream& stream() const { return stream_; }
  // Layers closed so far in the current component (0 before the first U).
  int32_t closed_layers() const { return closed_layers_; }
  const std::vector<WindowFinding>& window_findings() const { return findings_; }
  const GrammarOptions& options() const { return options_; }

 private:
  struct Checkpoint {
    size_t token_index;
    GrammarPhase phase;
    int32_t layer, n_prev, closed_layers;
    int64_t vertices_total;
    size_t components, findings;
  };

  // A refusal; its message (`why()`, spec reference included) is built only when wanted.
  template <class Why>
  Rejection Reject(RejectReason r, int32_t id, Why&& why) const {
    return messages_ ? MakeRejection(r, id, why()) : Rejection{r, std::string()};
  }
  Rejection MakeRejection(RejectReason r, int32_t id, const std::string& why) const;
  void StartLayer();
  void ResetLayerState();
  bool WindowOk(int32_t n_size, int32_t w) const;
  int32_t BudgetMaxSize(int64_t extra) const;
  bool FarFromCap(int64_t extra = 0) const;
  Rejection Step(int32_t id, bool commit);
  void ComputeMask();
  int64_t RowFinishCost(int32_t n_size, int64_t future) const;
  int64_t FutureRowsCost(int32_t from_row, int32_t n_size) const;
  bool ColumnsClear(int32_t s, int32_t c) const;
  std::string ExplainClose(int32_t n_size) const;
  void CloseLayer();
  void RecordFindings();

  // The rule table (grammar_rules.h): one row per phase, read by Step and ComputeMask alike.
  static const GrammarPhaseRule& RuleRow(GrammarPhase p);
  // Gates: predicates that hold for all ids of a class or for none (grammar_predicates.cpp).
  Rejection NotEnded(int32_t id) const;
  Rejection RoomForToken(int32_t id) const;
  Rejection RoomForComponent(int32_t id) const;
  Rejection RefuseEndAfterRoot(int32_t id) const;
  Rejection LayerClosable(int32_t id) const;
  Rejection BelowLayerIndexLimit(int32_t id) const;
  Rejection RoomForLayer(int32_t id) const;
  Rejection RoomForEos(int32_t id) const;
  Rejection BelowLayerSizeLimit(int32_t id) const;
  Rejection RoomForVertex(int32_t id) const;
  Rejection RoomToCloseAfterB(int32_t id) const;
  Rejection RowCanFinish(int32_t id) const;
  // Id-dependent predicates and their bulk forms (one shared description per pair).
  Rejection TestPosition(int32_t id) const;
  void AddPositions(TokenMask* mask) const;
  Rejection TestWindow(int32_t id) const;
  void AddWindows(TokenMask* mask) const;
  Rejection TestX(int32_t id) const;
  void AddX(TokenMask* mask) const;
  Rejection TestB(int32_t id) const;
  void AddB(TokenMask* mask) const;
  // Their shared descriptions.
  template <class F>
  void ForEachLinkedPosition(F&& f) const;
  WindowSizeRule WindowRuleNow() const;
  bool ChainLets(int32_t w) const;
  LayerSizeSet WindowSizes(const WindowSizeRule& rule, int32_t w, bool any = false) const;
  XRowRule XRuleAt(int32_t b, int32_t n_size, bool tight, int64_t future, int64_t rem) const;
  template <class F>
  void ForEachXRule(F&& f) const;
  int32_t BMinStart() const;
  uint32_t BCasesAt(int32_t s) const;
  // What an admitted id does (grammar.cpp).
  void ApplyEos(int32_t id);
  void ApplyComponentStart(int32_t id);
  void ApplyBlock(int32_t id);
  void ApplyOffset(int32_t id);
  void ApplyRootLayerEnd(int32_t id);
  void ApplyWindow(int32_t id);
  void ApplyX(int32_t id);
  void ApplyFirstB(int32_t id);
  void ApplyNextB(int32_t id);
  void ApplyLayerEnd(int32_t id);

  StreamLayer& cur_layer() { return stream_.components.back().layers.back(); }
  const StreamLayer& cur_layer() const { return stream_.components.back().layers.back(); }
  const StreamLayer& prev_layer() const {
    const auto& ls = stream_.components.back().layers;
    return ls[ls.size() - 2];
  }
  int32_t remaining() const;  // tokens still allowed (incl. EOS), large if unlimited

  GrammarOptions options_;
  GrammarPhase phase_ = GrammarPhase::kStart;
  std::vector<int32_t> history_;
  std::vector<Checkpoint> checkpoints_;
  LayeredStream stream_;
  std::vector<WindowFinding> findings_;
  int32_t layer_ = 0, n_prev_ = 0, closed_layers_ = 0;
  int64_t vertices_total_ = 0;

  // Current layer: sizes at which it can still close; incoming forward X distances per row.
  LayerSizeSet sizes_;
  std::array<LayerSizeSet, 200> incoming_{};
  std::array<uint8_t, 200> incoming_count_{};
  int32_t incoming_total_ = 0;
  // Current row.
  LayerSizeSet row_sizes_;
  std::array<uint8_t, 256> matched_{};
  std::array<uint8_t, 200> g_desc_{};
  int32_t g_count_ = 0, last_x_ = -1, last_s_ = -1, last_c_ = -1;
  LayerSizeSet eq_cols_;  // previous-layer columns at the current vertex's position
  bool eq_cols_any_ = false;
  int32_t pending_block_ = -1;
  // The layer sizes the id under test leaves open: written by the S and X tests and the B gate
  // of phase kAfterS, read by the matching Apply (Step runs them back to back).
  mutable LayerSizeSet next_sizes_;

  TokenMask mask_;
  bool mask_valid_ = false;
  bool messages_ = true;  // Check(id, false) turns refusal texts off for one call
};

// Checks a whole id array; returns the first rejection with its position in `*position`.
Rejection CheckTokens(const std::vector<int32_t>& ids, const GrammarOptions& options, size_t* position,
                      bool require_end = true);

}  // namespace silk
