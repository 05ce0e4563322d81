// SPDX-License-Identifier: MIT
// Face guidance's stages (runtime/sampling/face_guide_stage.h): the faces each legal B id,
// position or in-layer link would close, scored by FaceGuide, turned into a narrower mask (hard)
// or logit penalties (soft).
#include "runtime/sampling/face_guide_stage.h"

#include <algorithm>
#include <array>
#include <bitset>
#include <chrono>
#include <cmath>
#include <cstring>

#include "decoder/grammar.h"
#include "runtime/generation_stats.h"
#include "tokenizer/adjacency/between_layer_cases.h"
#include "tokenizer/adjacency/self_layer_decoder.h"
#include "tokenizer/packing/vertex_codec.h"
#include "tokenizer/vocabulary_layout.h"

namespace silk {

namespace {

using Clock = std::chrono::steady_clock;
using Columns = std::bitset<256>;
constexpr double kUnscored = -1;
// Hard form's fallback: the legal B ids scoring within this factor of the best are kept.
constexpr double kFallbackSlack = 1.25;

// The previous-layer columns a row's B tokens join (token_format.md §7).
void AddRowColumns(const std::vector<BetweenToken>& row, Columns* out) {
  for (const BetweenToken& t : row) {
    out->set(static_cast<size_t>(t.start));
    const int32_t pattern = BetweenCasePattern(t.kase);
    for (int32_t p = 1; p <= kBetweenWindow; ++p)
      if ((pattern >> (p - 1)) & 1) out->set(static_cast<size_t>(t.start + p));
  }
}

class FaceGuideStage : public SamplerStage {
 public:
  FaceGuideStage(const FaceGuide* guide, FaceGuidance mode, const Grammar* grammar, GenerationStats* stats)
      : guide_(guide), mode_(mode), grammar_(grammar), stats_(stats ? stats : &own_stats_) {}

  void Apply(SamplerCandidates* c) override {
    if (c->forced >= 0) return;
    const GrammarPhase phase = grammar_->phase();
    if (phase != GrammarPhase::kWantK && phase != GrammarPhase::kWantO && phase != GrammarPhase::kWantS &&
        phase != GrammarPhase::kAfterS && phase != GrammarPhase::kAfterB)
      return;
    if (!PrepareLayer()) return;
    const auto t0 = Clock::now();
    scored_.clear();
    if (phase == GrammarPhase::kWantO) {
      ScoreOffsets(*c->mask);
    } else if (phase == GrammarPhase::kWantK) {
      ScoreBlocks(*c->mask);  // a layer's first vertex
    } else if (phase == GrammarPhase::kWantS) {
      ScoreLinks(*c->mask);  // the window
    } else {
      PrepareVertex();
      ScoreBetween(*c->mask);
      ScoreBlocks(*c->mask);  // after a B, the next vertex's block is legal too
    }
    const size_t links = scored_.size();
    if (phase == GrammarPhase::kAfterS) ScoreLinks(*c->mask);  // X ids, beside the B ids
    if (!scored_.empty()) Decide(c, links == 0 ? scored_.size() : links);
    stats_->seconds.face_guidance += std::chrono::duration<double>(Clock::now() - t0).count();
  }

 private:
  bool PrepareLayer();
  void LoadPreviousLayer();
  void PrepareVertex();
  void LoadApexes(const StreamLayer& prev, const StreamLayer* before);
  double LinkedFace(int32_t a, int32_t c);
  double Pair(size_t entry);
  double FanFolds(const Columns& cols, int32_t c_new);
  double LinkedPairFolds(const Columns& cols, int32_t c_new);
  double IdScore(int32_t id, double enough);
  void ScoreBetween(const TokenMask& mask);
  void ScoreOffsets(const TokenMask& mask);
  void ScoreBlocks(const TokenMask& mask);
  // What a new row of the layer must join before its position is chosen (PositionScore): the
  // row being placed (position_) or a later row an S or X id links (later_row_), each its own.
  struct NewRow {
    int32_t row = -1;                                       // the row its folds were prepared for (PrepareInLayerFolds)
    std::vector<int32_t> linked_rows, near_columns;         // linked earlier rows, columns near it
    std::vector<std::pair<int32_t, int32_t>> linked_pairs;  // linked rows linked to each other
    // The earlier rows' columns; for each linked pair, the third corners of the triangles
    // already on its edge (CSR); the pairs of linked pairs that share a row s, as (s, x, y):
    // faces (s, x, p) and (s, y, p) share edge (s, p).
    std::vector<Columns> rows;
    std::vector<int32_t> pair_apex_begin;
    std::vector<QVec> pair_apex;
    std::vector<std::array<int32_t, 3>> fan_pairs;
    // For each linked row a and column c it joins (face (p, a, w_c) if p's first B joins c): the
    // third corners of the triangles already on edge (a, w_c), CSR over the (a, c) entries.
    std::vector<std::array<int32_t, 3>> col_faces;  // (a, c, end of its apexes in col_apex)
    std::vector<QVec> col_apex;
  };
  void PreparePosition(int32_t b, const QVec& centre);
  void NearColumns(const QVec& centre, NewRow* r) const;
  void PrepareInLayerFolds(int32_t b, NewRow* r) const;
  double InLayerFolds(const NewRow& r, const QVec& p, double enough) const;
  double ColumnFaces(const NewRow& r, const QVec& p, int32_t c, double enough) const;
  double PositionScore(const NewRow& r, const QVec& p, bool interior_only, double enough) const;
  void ScoreLinks(const TokenMask& mask);
  double LaterRow(int32_t d);
  void Decide(SamplerCandidates* c, size_t main_end);

  const FaceGuide* guide_;
  FaceGuidance mode_;
  const Grammar* grammar_;
  GenerationStats own_stats_;
  GenerationStats* stats_;
  // The previous layer (per layer): positions, nearest input points, self-layer adjacency (CSR).
  size_t layer_components_ = 0, layer_count_ = 0;
  bool layer_ok_ = false;
  std::vector<QVec> prev_pos_;
  std::vector<int32_t> prev_near_, adj_begin_, adj_;
  // Per adjacency entry (c, c'): the apexes of the triangles already on edge (w_c, w_c') (the
  // layer before the previous one, or the previous layer itself), CSR.
  std::vector<int32_t> apex_begin_;
  std::vector<QVec> apex_;
  // The vertex being written (per vertex): its edge and linked-face scores per column, the
  // scores of the triangles it makes with previous-layer edges (lazy, per adjacency entry).
  int32_t vertex_ = -1;
  QVec u_;
  int32_t u_near_ = -1;
  std::vector<double> edge_, linked_, pair_;
  // The earlier rows of the vertex's layer: their columns, and whether they are linked to it.
  std::vector<Columns> rows_;
  std::vector<char> row_linked_;
  std::vector<std::pair<int32_t, int32_t>> linked_list_;  // (linked row, column it joins)
  // This step: the row's columns so far and each column's score with them.
  Columns row_;
  std::vector<double> column_;
  std::vector<std::pair<double, int32_t>> scored_;  // (score, id) of the legal ids judged
  NewRow position_, later_row_;                     // K and O steps' new row; LaterRow's
  int32_t blocks_vertex_ = -1;                      // the row whose block scores block_score_ holds
  // S and X ids (per vertex, row links_vertex_): each later row b + d's best position score with
  // the links already stated to it and one from row b, LaterRow; index d.
  int32_t links_vertex_ = -1;
  std::vector<double> later_ = std::vector<double>(vocab::k_layer_vertex_limit + 1, kUnscored);
  std::vector<double> block_score_ = std::vector<double>(512, kUnscored);
  std::vector<std::pair<int32_t, float>> penalties_;
  TokenMask guided_;
};

// Earlier row a of a layer states an edge to row j > a (its window or an X reaches j).
bool Linked(const std::vector<StreamVertex>& vs, int32_t a, int32_t j) {
  const int32_t d = j - a;
  if (d <= vocab::k_self_window) return ((vs[a].window >> (d - 1)) & 1) != 0;
  return std::find(vs[a].extras.begin(), vs[a].extras.end(), d - 1) != vs[a].extras.end();
}

// The previous layer's part, once per layer; false when there is no previous layer to join
// (cannot happen in these phases) or it does not decode.
bool FaceGuideStage::PrepareLayer() {
  const LayeredStream& st = grammar_->stream();
  if (st.components.empty() || st.components.back().layers.size() < 2) return false;
  const size_t layers = st.components.back().layers.size();
  if (st.components.size() == layer_components_ && layers == layer_count_) return layer_ok_;
  layer_components_ = st.components.size();
  layer_count_ = layers;
  vertex_ = -1;
  blocks_vertex_ = -1;
  position_.row = -1;
  links_vertex_ = -1;
  LoadPreviousLayer();
  return layer_ok_;
}

void FaceGuideStage::LoadPreviousLayer() {
  const auto& layers = grammar_->stream().components.back().layers;
  const StreamLayer& prev = layers[layers.size() - 2];
  const int32_t n = static_cast<int32_t>(prev.vertices.size());
  prev_pos_.resize(static_cast<size_t>(n));
  prev_near_.resize(static_cast<size_t>(n));
  for (int32_t i = 0; i < n; ++i) {
    prev_pos_[i] = prev.vertices[i].pos;
    prev_near_[i] = guide_->NearestPoint(prev_pos_[i]);
  }
  adj_begin_.assign(static_cast<size_t>(n) + 1, 0);
  adj_.clear();
  apex_begin_.assign(1, 0);
  apex_.clear();
  layer_ok_ = true;
  if (layers.size() == 2) return;  // the previous layer is the root: no self-layer edges
  auto edges = DecodeSelfLayer(prev);
  if (!edges.ok()) {
    layer_ok_ = false;  // a closed layer the grammar accepted always decodes; judge nothing if not
    return;
  }
  for (const auto& [a, b] : *edges) ++adj_begin_[a + 1], ++adj_begin_[b + 1];
  for (int32_t i = 0; i < n; ++i) adj_begin_[i + 1] += adj_begin_[i];
  adj_.resize(static_cast<size_t>(adj_begin_[n]));
  std::vector<int32_t> fill(adj_begin_.begin(), adj_begin_.end() - 1);
  for (const auto& [a, b] : *edges) adj_[fill[a]++] = b, adj_[fill[b]++] = a;
  LoadApexes(prev, &layers[layers.size() - 3]);
}

// For each adjacency entry (c, c') of the previous layer, the third corners of the triangles
// already on edge (w_c, w_c'): vertices of the layer before whose columns both rows join, and
// previous-layer vertices adjacent to both. A new face on that edge must not fold onto them.
void FaceGuideStage::LoadApexes(const StreamLayer& prev, const StreamLayer* before) {
  const int32_t n = static_cast<int32_t>(prev_pos_.size());
  std::vector<Columns> cols(static_cast<size_t>(n));
  for (int32_t i = 0; i < n; ++i) AddRowColumns(prev.vertices[i].between, &cols[i]);
  apex_begin_.assign(adj_.size() + 1, 0);
  apex_.clear();
  for (int32_t c = 0; c < n; ++c)
    for (int32_t e = adj_begin_[c]; e < adj_begin_[c + 1]; ++e) {
      const int32_t c2 = adj_[e];
      const Columns common = cols[c] & cols[c2];
      for (size_t z = 0; z < before->vertices.size() && z < common.size(); ++z)
        if (common.test(z)) apex_.push_back(before->vertices[z].pos);
      for (int32_t f = adj_begin_[c]; f < adj_begin_[c + 1]; ++f)
        for (int32_t g = adj_begin_[c2]; g < adj_begin_[c2 + 1]; ++g)
          if (adj_[f] == adj_[g]) apex_.push_back(prev_pos_[adj_[f]]);
      apex_begin_[e + 1] = static_cast<int32_t>(apex_.size());
    }
}

// The vertex's new edges alone, and the faces (u, a, w_c) with an earlier vertex a of its layer
// it is linked to (a's window or X reached it) whose row joins column c.
void FaceGuideStage::PrepareVertex() {
  const auto& vs = grammar_->stream().components.back().layers.back().vertices;
  const int32_t b = static_cast<int32_t>(vs.size()) - 1, n = static_cast<int32_t>(prev_pos_.size());
  if (b == vertex_) return;
  vertex_ = b;
  u_ = vs[b].pos;
  u_near_ = guide_->NearestPoint(u_);
  edge_.resize(static_cast<size_t>(n));
  linked_.assign(static_cast<size_t>(n), 0);
  pair_.assign(adj_.size(), kUnscored);
  column_.resize(static_cast<size_t>(n));
  rows_.resize(static_cast<size_t>(b));
  row_linked_.resize(static_cast<size_t>(b));
  linked_list_.clear();
  for (int32_t c = 0; c < n; ++c) edge_[c] = guide_->EdgeScore(u_, prev_pos_[c]);
  for (int32_t a = 0; a < b; ++a) {
    rows_[a].reset();
    AddRowColumns(vs[a].between, &rows_[a]);
    row_linked_[a] = Linked(vs, a, b);
    if (!row_linked_[a]) continue;
    for (int32_t c = 0; c < n; ++c)
      if (rows_[a].test(static_cast<size_t>(c))) linked_list_.push_back({a, c});
  }
  for (const auto& [a, c] : linked_list_) linked_[c] = std::max(linked_[c], LinkedFace(a, c));
}

// Face (u, a, w_c) of linked row a joining column c: its own score and its folds onto the faces
// already on its edges: (a, w_c) with a's faces (a, w_c, w_m) and rows a' next to a joining c;
// (u, w_c) with another linked row's face (u, a', w_c); (u, a) with faces (u, a, a').
double FaceGuideStage::LinkedFace(int32_t a, int32_t c) {
  const auto& vs = grammar_->stream().components.back().layers.back().vertices;
  const int32_t b = static_cast<int32_t>(rows_.size());
  const QVec &pa = vs[a].pos, &w = prev_pos_[c];
  double s = guide_->FaceScore(u_, pa, w, u_near_, guide_->NearestPoint(pa), prev_near_[c]);
  for (int32_t e = adj_begin_[c]; e < adj_begin_[c + 1]; ++e)
    if (rows_[a].test(static_cast<size_t>(adj_[e]))) s = std::max(s, guide_->FoldScore(pa, w, u_, prev_pos_[adj_[e]]));
  for (int32_t a2 = 0; a2 < b; ++a2) {
    if (a2 == a) continue;
    const bool next_to_a = a2 < a ? Linked(vs, a2, a) : Linked(vs, a, a2);
    const QVec& p2 = vs[a2].pos;
    if (next_to_a && rows_[a2].test(static_cast<size_t>(c))) s = std::max(s, guide_->FoldScore(pa, w, u_, p2));
    if (row_linked_[a2] && rows_[a2].test(static_cast<size_t>(c))) s = std::max(s, guide_->FoldScore(u_, w, pa, p2));
    if (row_linked_[a2] && next_to_a) s = std::max(s, guide_->FoldScore(u_, pa, w, p2));
  }
  return s;
}

// Triangle (u, w_c, w_c') of adjacency entry `entry` (c' = adj_[entry]), computed once.
double FaceGuideStage::Pair(size_t entry) {
  if (pair_[entry] != kUnscored) return pair_[entry];
  const int32_t c2 = adj_[entry];
  const int32_t c1 =
      static_cast<int32_t>(std::upper_bound(adj_begin_.begin(), adj_begin_.end(), static_cast<int32_t>(entry)) -
                           adj_begin_.begin()) -
      1;
  const QVec &w1 = prev_pos_[c1], &w2 = prev_pos_[c2];
  double s = guide_->FaceScore(u_, w1, w2, u_near_, prev_near_[c1], prev_near_[c2]);
  // Folds: onto the faces already on edge (w1, w2); onto an earlier row's face there (a third
  // face); onto a linked row's face (u, w, a) on edge (u, w1) or (u, w2).
  for (int32_t k = apex_begin_[entry]; k < apex_begin_[entry + 1]; ++k)
    s = std::max(s, guide_->FoldScore(w1, w2, u_, apex_[static_cast<size_t>(k)]));
  const auto& vs = grammar_->stream().components.back().layers.back().vertices;
  for (size_t a = 0; a < rows_.size(); ++a) {
    const bool has1 = rows_[a].test(static_cast<size_t>(c1)), has2 = rows_[a].test(static_cast<size_t>(c2));
    if (has1 && has2) s = std::max(s, guide_->FoldScore(w1, w2, u_, vs[a].pos));
    if (!row_linked_[a]) continue;
    if (has1) s = std::max(s, guide_->FoldScore(u_, w1, w2, vs[a].pos));
    if (has2) s = std::max(s, guide_->FoldScore(u_, w2, w1, vs[a].pos));
  }
  pair_[entry] = s;
  return s;
}

// Folds among the vertex's own faces (u, w_c, w_m) around edge (u, w_c) that new column c_new
// takes part in, given all the columns `cols` the row would join: as the middle c, or as one
// side with a neighbour m of it in the middle.
double FaceGuideStage::FanFolds(const Columns& cols, int32_t c_new) {
  double worst = 0;
  auto around = [&](int32_t c, int32_t must) {  // pairs of c's neighbours in cols (one of them `must`, if >= 0)
    for (int32_t e = adj_begin_[c]; e < adj_begin_[c + 1]; ++e) {
      const int32_t m1 = adj_[e];
      if (!cols.test(static_cast<size_t>(m1))) continue;
      for (int32_t f = e + 1; f < adj_begin_[c + 1]; ++f) {
        const int32_t m2 = adj_[f];
        if (!cols.test(static_cast<size_t>(m2)) || (must >= 0 && m1 != must && m2 != must)) continue;
        worst = std::max(worst, guide_->FoldScore(u_, prev_pos_[c], prev_pos_[m1], prev_pos_[m2]));
      }
    }
  };
  around(c_new, -1);
  for (int32_t e = adj_begin_[c_new]; e < adj_begin_[c_new + 1]; ++e)
    if (cols.test(static_cast<size_t>(adj_[e]))) around(adj_[e], c_new);
  return worst;
}

// Folds on edge (u, a) between the faces (u, a, w_c) and (u, a, w_m) of a linked row a joining
// both columns, c = c_new, m any column in `cols`.
double FaceGuideStage::LinkedPairFolds(const Columns& cols, int32_t c_new) {
  const auto& vs = grammar_->stream().components.back().layers.back().vertices;
  double worst = 0;
  for (const auto& [a, c] : linked_list_)
    if (c == c_new)
      for (const auto& [a2, m] : linked_list_)
        if (a2 == a && m != c && cols.test(static_cast<size_t>(m)))
          worst = std::max(worst, guide_->FoldScore(u_, vs[a].pos, prev_pos_[c], prev_pos_[m]));
  return worst;
}

// The worst face or edge id (s, case) would add, given the row's columns so far (column_);
// work stops once it exceeds `enough`.
double FaceGuideStage::IdScore(int32_t id, double enough) {
  const int32_t s = (id - vocab::kBBegin) / kBetweenCases,
                pattern = BetweenCasePattern((id - vocab::kBBegin) % kBetweenCases);
  const uint32_t window = 1u | (static_cast<uint32_t>(pattern) << 1);  // bit p: column s + p
  const int32_t n = static_cast<int32_t>(prev_pos_.size());
  double worst = 0;
  Columns cols = row_;
  for (int32_t p = 0; p <= kBetweenWindow; ++p)
    if (((window >> p) & 1) && s + p < n) cols.set(static_cast<size_t>(s + p));
  for (int32_t p = 0; p <= kBetweenWindow; ++p) {
    const int32_t c = s + p;
    if (!((window >> p) & 1) || c >= n) continue;
    worst = std::max(worst, column_[c]);
    if (worst > enough) return worst;
    for (int32_t e = adj_begin_[c]; e < adj_begin_[c + 1]; ++e) {
      const int32_t q = adj_[e] - s;  // a neighbour inside this id's own segment
      if (q > p && q <= kBetweenWindow && ((window >> q) & 1)) worst = std::max(worst, Pair(static_cast<size_t>(e)));
    }
    if (worst > enough) return worst;
    worst = std::max(worst, FanFolds(cols, c));
    worst = std::max(worst, LinkedPairFolds(cols, c));
  }
  return worst;
}

void FaceGuideStage::ScoreBetween(const TokenMask& mask) {
  const auto& vs = grammar_->stream().components.back().layers.back().vertices;
  row_.reset();
  AddRowColumns(vs[vertex_].between, &row_);
  const int32_t n = static_cast<int32_t>(prev_pos_.size());
  for (int32_t col = 0; col < n; ++col) {
    double w = std::max(edge_[col], linked_[col]);
    for (int32_t e = adj_begin_[col]; e < adj_begin_[col + 1]; ++e)
      if (row_.test(static_cast<size_t>(adj_[e]))) w = std::max(w, Pair(static_cast<size_t>(e)));
    column_[col] = w;
  }
  // Hard: a score past 1 only removes the id unless none passes (then the exact scores).
  const double enough = mode_ == FaceGuidance::kHard ? 1.0 : HUGE_VAL;
  const size_t first = scored_.size();
  bool any_pass = false;
  for (int32_t id = mask.Next(vocab::kBBegin); id >= 0 && id < vocab::kBEnd; id = mask.Next(id + 1)) {
    scored_.push_back({IdScore(id, enough), id});
    any_pass = any_pass || scored_.back().first <= 1;
  }
  if (any_pass || enough == HUGE_VAL) return;
  for (size_t i = first; i < scored_.size(); ++i) scored_[i].first = IdScore(scored_[i].second, HUGE_VAL);
}

// What a new vertex (row b) must join, for PositionScore: the earlier rows of its layer that
// stated an edge to it, the pairs of those rows joined to each other, and the previous layer's
// kNearColumns vertices nearest `centre` (its first B joins one of them).
void FaceGuideStage::PreparePosition(int32_t b, const QVec& centre) {
  const auto& vs = grammar_->stream().components.back().layers.back().vertices;
  NewRow& r = position_;
  r.linked_rows.clear();
  r.linked_pairs.clear();
  for (int32_t a = 0; a < b; ++a)
    if (Linked(vs, a, b)) r.linked_rows.push_back(a);
  for (size_t i = 0; i < r.linked_rows.size(); ++i)
    for (size_t j = i + 1; j < r.linked_rows.size(); ++j)
      if (Linked(vs, r.linked_rows[i], r.linked_rows[j]))
        r.linked_pairs.push_back({r.linked_rows[i], r.linked_rows[j]});
  if (b != r.row) PrepareInLayerFolds(b, &r);
  NearColumns(centre, &r);
}

// The previous layer's kNearColumns vertices nearest `centre` (a new vertex's first B joins one).
void FaceGuideStage::NearColumns(const QVec& centre, NewRow* r) const {
  constexpr size_t kNearColumns = 4;
  auto dist2 = [&](int32_t c) {
    const QVec& q = prev_pos_[c];
    return (q.x - centre.x) * (q.x - centre.x) + (q.y - centre.y) * (q.y - centre.y) +
           (q.z - centre.z) * (q.z - centre.z);
  };
  std::vector<int32_t>& near = r->near_columns;
  near.resize(prev_pos_.size());
  for (size_t c = 0; c < near.size(); ++c) near[c] = static_cast<int32_t>(c);
  const size_t n = std::min(kNearColumns, near.size());
  std::partial_sort(near.begin(), near.begin() + n, near.end(),
                    [&](int32_t x, int32_t y) { return dist2(x) < dist2(y) || (dist2(x) == dist2(y) && x < y); });
  near.resize(n);
}

// The in-layer faces (a1, a2, p) a position p closes with each linked pair can fold onto the
// triangles already on edge (a1, a2) (a row next to both, a previous-layer vertex both rows
// join) and onto each other around p. Their parts that do not depend on p, once per new row b
// (a later row, LaterRow: of the rows written so far).
void FaceGuideStage::PrepareInLayerFolds(int32_t b, NewRow* r) const {
  const auto& vs = grammar_->stream().components.back().layers.back().vertices;
  auto next_to = [&](int32_t x, int32_t y) { return x < y ? Linked(vs, x, y) : Linked(vs, y, x); };
  r->row = b;
  b = std::min(b, static_cast<int32_t>(vs.size()));
  r->rows.resize(static_cast<size_t>(b));
  for (int32_t a = 0; a < b; ++a) {
    r->rows[a].reset();
    AddRowColumns(vs[a].between, &r->rows[a]);
  }
  r->pair_apex_begin.assign(1, 0);
  r->pair_apex.clear();
  r->fan_pairs.clear();
  const auto& pairs = r->linked_pairs;
  for (size_t k = 0; k < pairs.size(); ++k) {
    const auto [a1, a2] = pairs[k];
    for (int32_t a3 = 0; a3 < b; ++a3)
      if (a3 != a1 && a3 != a2 && next_to(a3, a1) && next_to(a3, a2)) r->pair_apex.push_back(vs[a3].pos);
    const Columns common = r->rows[a1] & r->rows[a2];
    for (size_t c = 0; c < prev_pos_.size() && c < common.size(); ++c)
      if (common.test(c)) r->pair_apex.push_back(prev_pos_[c]);
    r->pair_apex_begin.push_back(static_cast<int32_t>(r->pair_apex.size()));
    for (size_t j = k + 1; j < pairs.size(); ++j) {
      const auto [b1, b2] = pairs[j];
      if (a1 == b1 || a1 == b2) r->fan_pairs.push_back({a1, a2, a1 == b1 ? b2 : b1});
      if (a2 == b1 || a2 == b2) r->fan_pairs.push_back({a2, a1, a2 == b1 ? b2 : b1});
    }
  }
  r->col_faces.clear();
  r->col_apex.clear();
  for (int32_t a : r->linked_rows)
    for (int32_t c = 0; c < static_cast<int32_t>(prev_pos_.size()); ++c) {
      if (!r->rows[a].test(static_cast<size_t>(c))) continue;
      for (int32_t a2 = 0; a2 < b; ++a2)
        if (a2 != a && next_to(a2, a) && r->rows[a2].test(static_cast<size_t>(c))) r->col_apex.push_back(vs[a2].pos);
      for (int32_t e = adj_begin_[c]; e < adj_begin_[c + 1]; ++e)
        if (r->rows[a].test(static_cast<size_t>(adj_[e]))) r->col_apex.push_back(prev_pos_[adj_[e]]);
      r->col_faces.push_back({a, c, static_cast<int32_t>(r->col_apex.size())});
    }
}

// Faces (p, a, w_c) that p's first B closes if it joins column c, with each linked row a that
// joins c: their distance part and folds onto the triangles on edge (a, w_c), onto each other
// around edge (p, w_c), and onto the in-layer faces (p, a, a2) around edge (p, a).
double FaceGuideStage::ColumnFaces(const NewRow& r, const QVec& p, int32_t c, double enough) const {
  const auto& vs = grammar_->stream().components.back().layers.back().vertices;
  const QVec& w = prev_pos_[c];
  double worst = 0;
  for (size_t k = 0; k < r.col_faces.size() && worst <= enough; ++k) {
    const auto [a, kc, end] = r.col_faces[k];
    if (kc != c) continue;
    const QVec& pa = vs[a].pos;
    worst = std::max(worst, guide_->FaceDistance(p, pa, w));
    for (int32_t i = k == 0 ? 0 : r.col_faces[k - 1][2]; i < end; ++i)
      worst = std::max(worst, guide_->FoldScore(pa, w, p, r.col_apex[static_cast<size_t>(i)]));
    for (size_t j = k + 1; j < r.col_faces.size(); ++j)
      if (r.col_faces[j][1] == c) worst = std::max(worst, guide_->FoldScore(p, w, pa, vs[r.col_faces[j][0]].pos));
    for (const auto& [a1, a2] : r.linked_pairs)
      if (a1 == a || a2 == a) worst = std::max(worst, guide_->FoldScore(p, pa, w, vs[a1 == a ? a2 : a1].pos));
  }
  return worst;
}

// The worst fold of the faces position p closes with the linked pairs (PrepareInLayerFolds).
double FaceGuideStage::InLayerFolds(const NewRow& r, const QVec& p, double enough) const {
  const auto& vs = grammar_->stream().components.back().layers.back().vertices;
  double worst = 0;
  for (size_t k = 0; k < r.linked_pairs.size() && worst <= enough; ++k) {
    const QVec &p1 = vs[r.linked_pairs[k].first].pos, &p2 = vs[r.linked_pairs[k].second].pos;
    for (int32_t i = r.pair_apex_begin[k]; i < r.pair_apex_begin[k + 1]; ++i)
      worst = std::max(worst, guide_->FoldScore(p1, p2, p, r.pair_apex[static_cast<size_t>(i)]));
  }
  for (const auto& [s, x, y] : r.fan_pairs) {
    if (worst > enough) break;
    worst = std::max(worst, guide_->FoldScore(vs[s].pos, p, vs[x].pos, vs[y].pos));
  }
  return worst;
}

// A position fixes the vertex's edges to the linked rows, the faces among them, and where its
// first B can go: the worst of those (distance only), the B part being the best edge to a near
// column. interior_only: edges without their ends (a representative cell of a block). Work
// stops once the score is known to exceed `enough` (the caller keeps only smaller ones).
double FaceGuideStage::PositionScore(const NewRow& r, const QVec& p, bool interior_only, double enough) const {
  const auto& vs = grammar_->stream().components.back().layers.back().vertices;
  auto edge = [&](const QVec& q) { return interior_only ? guide_->EdgeInterior(q, p) : guide_->EdgeScore(q, p); };
  double worst = 0;
  for (int32_t a : r.linked_rows) worst = std::max(worst, edge(vs[a].pos));
  for (const auto& [a1, a2] : r.linked_pairs) {
    if (worst > enough) return worst;
    worst = std::max(worst, guide_->FaceDistance(vs[a1].pos, vs[a2].pos, p));
  }
  if (worst <= enough) worst = std::max(worst, InLayerFolds(r, p, enough));
  if (worst > enough || r.near_columns.empty()) return worst;
  double column = HUGE_VAL;
  for (int32_t c : r.near_columns) {
    double cs = edge(prev_pos_[c]);
    if (cs < column) cs = std::max(cs, ColumnFaces(r, p, c, std::min(column, enough)));
    column = std::min(column, cs);
    if (column <= worst) break;  // the linked part decides
  }
  return std::max(worst, column);
}

// O ids after the block just taken: each position's score.
void FaceGuideStage::ScoreOffsets(const TokenMask& mask) {
  const int32_t b = static_cast<int32_t>(grammar_->stream().components.back().layers.back().vertices.size()) - 1;
  const int32_t block = grammar_->tokens().back();
  PreparePosition(b, VertexOfTokens(block, vocab::kOBegin + 8 * 256 + 8 * 16 + 8));
  // Hard: a score past 1 only removes the id, unless none passes (then the exact scores, for the
  // fallback's best). Soft: penalties need them all.
  const double enough = mode_ == FaceGuidance::kHard ? 1.0 : HUGE_VAL;
  bool any_pass = false;
  for (int32_t id = mask.Next(vocab::kOBegin); id >= 0 && id < vocab::kOEnd; id = mask.Next(id + 1)) {
    scored_.push_back({PositionScore(position_, VertexOfTokens(block, id), false, enough), id});
    any_pass = any_pass || scored_.back().first <= 1;
  }
  if (any_pass || enough == HUGE_VAL) return;
  for (auto& [score, id] : scored_) score = PositionScore(position_, VertexOfTokens(block, id), false, HUGE_VAL);
}

// K ids (the next vertex's block, legal once a row has its B): each block's best of 8
// representative cells (offsets 4, 12 per axis; each cell of the block is within 4 sqrt 3 of
// one), edges without their ends; the offset step then judges the cells of the block taken.
// Representatives farther from the input than a vertex can be (the tolerance) plus 4 sqrt 3 are
// skipped, and a block stops at its first passing one (only scores above 1 matter, for the
// fallback and the penalties). A block's score depends only on the rows before the new vertex,
// so it is computed once per vertex.
void FaceGuideStage::ScoreBlocks(const TokenMask& mask) {
  const int32_t b = static_cast<int32_t>(grammar_->stream().components.back().layers.back().vertices.size());
  if (b != blocks_vertex_) {
    blocks_vertex_ = b;
    std::fill(block_score_.begin(), block_score_.end(), kUnscored);
  }
  const double reach = std::max(guide_->tolerance(), 2.0) + 4 * std::sqrt(3.0);
  for (int32_t id = mask.Next(vocab::kKBegin); id >= 0 && id < vocab::kKEnd; id = mask.Next(id + 1)) {
    double& best = block_score_[static_cast<size_t>(id - vocab::kKBegin)];
    if (best == kUnscored) {
      PreparePosition(b, VertexOfTokens(id, vocab::kOBegin + 8 * 256 + 8 * 16 + 8));
      best = HUGE_VAL;
      for (int32_t r = 0; r < 8 && best > 1; ++r) {
        const QVec q = VertexOfTokens(
            id, vocab::kOBegin + (4 + 8 * (r >> 2)) * 256 + (4 + 8 * ((r >> 1) & 1)) * 16 + 4 + 8 * (r & 1));
        if (guide_->CellDistance(q) <= reach) best = std::min(best, PositionScore(position_, q, true, best));
      }
    }
    scored_.push_back({best, id});
  }
}

// S and X ids: an in-layer link from the vertex (row b) to a later row b + d of its layer commits
// that row to faces with every row linked to it, before its position exists. Each id scores the
// worst of its later rows' best position scores (LaterRow), so a window or X id that leaves a
// later row no position whose faces pass is judged now, not at that row's fallback.
void FaceGuideStage::ScoreLinks(const TokenMask& mask) {
  const int32_t b = static_cast<int32_t>(grammar_->stream().components.back().layers.back().vertices.size()) - 1;
  if (b != links_vertex_) {
    links_vertex_ = b;
    std::fill(later_.begin(), later_.end(), kUnscored);
  }
  for (int32_t id = mask.Next(vocab::kXBegin); id >= 0 && id < vocab::kSEnd; id = mask.Next(id + 1)) {
    double worst = 0;
    if (id >= vocab::kSBegin) {
      for (int32_t d = 1; d <= vocab::k_self_window; ++d)
        if (((id - vocab::kSBegin) >> (d - 1)) & 1) worst = std::max(worst, LaterRow(d));
    } else {
      worst = LaterRow(id - vocab::kXBegin + 1);
    }
    scored_.push_back({worst, id});
  }
}

// The best PositionScore later row j = b + d could reach, linked to b and to the rows before b
// whose windows or X ids reach it (its first B to one of the previous-layer vertices nearest the
// links), over 27 candidate positions: the links' centroid first, then the lattice around it at
// half their spread. 0 when j has one linked row. The first passing candidate ends the search
// (only scores above 1 matter).
double FaceGuideStage::LaterRow(int32_t d) {
  double& score = later_[static_cast<size_t>(std::min(d, vocab::k_layer_vertex_limit))];
  if (score != kUnscored) return score;
  const auto& vs = grammar_->stream().components.back().layers.back().vertices;
  const int32_t b = static_cast<int32_t>(vs.size()) - 1, j = b + d;
  NewRow& r = later_row_;
  r.linked_rows.clear();
  r.linked_pairs.clear();
  for (int32_t a = 0; a < b; ++a)
    if (Linked(vs, a, j)) r.linked_rows.push_back(a);
  r.linked_rows.push_back(b);
  if (r.linked_rows.size() < 2) return score = 0;
  for (size_t i = 0; i + 1 < r.linked_rows.size(); ++i)
    for (size_t k = i + 1; k < r.linked_rows.size(); ++k)
      if (Linked(vs, r.linked_rows[i], r.linked_rows[k]))
        r.linked_pairs.push_back({r.linked_rows[i], r.linked_rows[k]});
  PrepareInLayerFolds(j, &r);
  double cx = 0, cy = 0, cz = 0, spread = 0;
  for (int32_t a : r.linked_rows) cx += vs[a].pos.x, cy += vs[a].pos.y, cz += vs[a].pos.z;
  const double n = static_cast<double>(r.linked_rows.size());
  cx /= n, cy /= n, cz /= n;
  for (int32_t a : r.linked_rows)
    spread = std::max(spread, std::hypot(vs[a].pos.x - cx, vs[a].pos.y - cy, vs[a].pos.z - cz));
  const double step = std::max(1.0, spread / 2);
  auto cell = [](double v) { return static_cast<int32_t>(std::clamp(std::lround(v), 0L, vocab::k_quant_bins - 1L)); };
  NearColumns({cell(cx), cell(cy), cell(cz)}, &r);
  score = HUGE_VAL;
  for (int32_t k = 0; k < 27 && score > 1; ++k) {
    const int32_t o[3] = {(k + 13) % 27 / 9 - 1, (k + 13) % 9 / 3 - 1, (k + 13) % 3 - 1};  // the centre first
    const QVec p{cell(cx + o[0] * step), cell(cy + o[1] * step), cell(cz + o[2] * step)};
    score = std::min(score, PositionScore(r, p, false, score));
  }
  return score;
}

// Hard: the judged ids scoring above 1 removed; when none of the step's own ids (scored_ before
// main_end: B, K, O, or S at a window step) passes, the ones within kFallbackSlack of their best
// stay (a fallback). X ids beside B ids (from main_end on) that fail are removed either way: a
// row must not take an extra in-layer link to escape its B ids' verdict. Ids not judged (U, E)
// stay. Soft: penalties for the ones above 1.
void FaceGuideStage::Decide(SamplerCandidates* c, size_t main_end) {
  double best = HUGE_VAL;
  for (size_t i = 0; i < main_end; ++i) best = std::min(best, scored_[i].first);
  ++stats_->face_guided_tokens;
  const bool none_pass = best > 1;
  stats_->face_fallbacks += none_pass ? 1 : 0;
  c->face = none_pass ? FaceVerdict::kFallback : FaceVerdict::kPassed;
  if (mode_ == FaceGuidance::kSoft) {
    penalties_.clear();
    for (const auto& [score, id] : scored_)
      if (score > 1)
        penalties_.push_back({id, static_cast<float>(std::min(kFaceSoftPenaltyMax, kFaceSoftPenalty * (score - 1)))});
    c->penalties = &penalties_;
    return;
  }
  guided_ = *c->mask;
  const double keep = none_pass ? best * kFallbackSlack : 1.0;
  for (size_t i = 0; i < scored_.size(); ++i)
    if (scored_[i].first > (i < main_end ? keep : 1.0)) guided_.Reset(scored_[i].second);
  c->mask = &guided_;
}

class FacePenaltyStage : public SamplerStage {
 public:
  void Apply(SamplerCandidates* c) override {
    if (!c->penalties || c->penalties->empty()) return;
    std::memcpy(logits_.data(), c->logits, sizeof(float) * logits_.size());
    for (const auto& [id, amount] : *c->penalties) logits_[id] = c->logits[id] - amount;
    c->logits = logits_.data();
  }

 private:
  std::vector<float> logits_ = std::vector<float>(vocab::k_model_vocab_size);
};

}  // namespace

std::unique_ptr<SamplerStage> MakeFaceGuideStage(const FaceGuide* guide, FaceGuidance mode, const Grammar* grammar,
                                                 GenerationStats* stats) {
  return std::make_unique<FaceGuideStage>(guide, mode, grammar, stats);
}

std::unique_ptr<SamplerStage> MakeFacePenaltyStage() { return std::make_unique<FacePenaltyStage>(); }

}  // namespace silk
