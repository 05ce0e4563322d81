// SPDX-License-Identifier: MIT
// Face recovery = growth (face_growth) + exact verification (face_verification) + a bounded
// local search that repairs the growth's answer where the replayed layering disagrees.
#include "tokenizer/face_recovery/face_recovery.h"

#include <algorithm>
#include <utility>

#include "tokenizer/face_recovery/face_fan_edits.h"
#include "tokenizer/face_recovery/face_pair_search.h"
#include "tokenizer/face_recovery/face_search_edits.h"

namespace silk {
namespace {

// Search budget per component, in units of one grow + verify pass over the graph
// (triangles + edges + vertices), and a cap on passes: keeps arbitrary token streams and
// defects the tokens cannot explain (unencoded edges, §5.4) cheap.
constexpr int64_t kSearchWork = int64_t{1} << 24;
constexpr int32_t kMaxEvaluations = 200;
// More defects than max(this, vertices / kVerticesPerRepairableDefect) after the growth: not
// a mesh the encoder produced (random or corrupted streams, e.g. grammar random walks); the
// growth's answer is returned unsearched.
constexpr int32_t kMaxDefectsToRepair = 48;
constexpr int32_t kVerticesPerRepairableDefect = 32;
// Look-ahead steps one search growth may spend, per unit (the first growth keeps the default).
constexpr int64_t kSearchLookAheadPerUnit = 8;
// The pairwise step (face_pair_search.h): only for sets this close to replaying exactly
// (real meshes' stuck components have a few defects; random streams many), and at most this
// many grow+verify passes per component over the whole search.
constexpr int32_t kMaxDefectsForPairs = 4;
constexpr int32_t kMaxPairEvaluations = 600;
// Root-fan restarts (a defect at the root that the search leaves): each a full search.
constexpr int32_t kMaxRootFans = 4;

}  // namespace

namespace {

// Per-search pass budgets (one grow + verify each).
struct SearchBudget {
  int32_t evals_left = 0;
  int32_t pair_evals_left = 0;
};

// Evaluates `edits` (consumed), keeping in *best the best strictly better than `cur`.
bool BestOf(const ComponentGraph& g, const SearchCandidate& cur, std::vector<GrowConstraints>* edits,
            int32_t* evals_left, SearchCandidate* best, bool have_best) {
  for (auto& e : *edits) {
    if (*evals_left <= 0) break;
    --*evals_left;
    SearchCandidate c = EvaluateCandidate(g, std::move(e));
    if (c.verification.BetterThan(have_best ? best->verification : cur.verification)) {
      *best = std::move(c);
      have_best = true;
    }
  }
  edits->clear();
  return have_best;
}

// The local search from `cur`: while defects remain, edits at the first suspect not yet
// exhausted; when all are exhausted, the pairwise step.
SearchCandidate Repair(const ComponentGraph& g, SearchCandidate cur, int64_t lookahead, SearchBudget* b,
                       FaceRecoveryStats* st) {
  std::vector<char> exhausted(static_cast<size_t>(g.vertex_count), 0);
  std::vector<GrowConstraints> edits;
  while (cur.verification.Score() > 0 && !st->search_budget_exhausted) {
    int32_t focus = -1;
    for (int32_t v : cur.verification.suspects) {
      if (!exhausted[static_cast<size_t>(v)]) {
        focus = v;
        break;
      }
    }
    if (focus < 0) {
      // No single edit at any suspect helps: two at once, for sets with few defects.
      if (cur.verification.Score() > kMaxDefectsForPairs) break;
      const int32_t before = b->pair_evals_left;
      SearchCandidate pair;
      const bool improved = FindImprovingPair(g, cur, lookahead, &b->pair_evals_left, &pair);
      st->pair_evaluations += before - b->pair_evals_left;
      if (!improved) break;
      cur = std::move(pair);
      std::fill(exhausted.begin(), exhausted.end(), 0);
      continue;
    }
    // One edit at the focus vertex (face_search_edits.h). A change is kept when it removes
    // a defect or moves the first defect later at the same count (a strict, well-founded
    // order, so the search cannot cycle).
    EditsAt(g, cur, focus, lookahead, &edits);
    const int32_t before = b->evals_left;
    SearchCandidate best;
    const bool have_best = BestOf(g, cur, &edits, &b->evals_left, &best, false);
    st->search_evaluations += before - b->evals_left;
    if (b->evals_left <= 0) st->search_budget_exhausted = true;
    if (have_best) {
      cur = std::move(best);
      std::fill(exhausted.begin(), exhausted.end(), 0);
    } else {
      exhausted[static_cast<size_t>(focus)] = 1;
    }
  }
  return cur;
}

}  // namespace

StatusOr<std::vector<std::array<int32_t, 3>>> RecoverFacesOfGraph(const ComponentGraph& g, FaceRecoveryStats* stats) {
  FaceRecoveryStats st;
  SearchCandidate grown = EvaluateCandidate(g, {}, &st);
  const int64_t unit = static_cast<int64_t>(g.triangles.size() + g.edges.size()) + g.vertex_count + 1;
  const int64_t lookahead = kSearchLookAheadPerUnit * unit;
  auto fresh_budget = [&] {
    SearchBudget b;
    b.evals_left = static_cast<int32_t>(std::min<int64_t>(kMaxEvaluations, kSearchWork / unit));
    b.pair_evals_left = static_cast<int32_t>(std::min<int64_t>(kMaxPairEvaluations, kSearchWork / unit));
    return b;
  };
  if (grown.verification.Score() > std::max(kMaxDefectsToRepair, g.vertex_count / kVerticesPerRepairableDefect))
    st.search_budget_exhausted = true;
  SearchBudget budget = fresh_budget();
  SearchCandidate cur = Repair(g, grown, lookahead, &budget, &st);
  // Still a defect at the root: every root fan the layer order allows, forced, each
  // followed by its own search (the fan usually disturbs more faces than it repairs, so
  // the search order alone never reaches it). At most kMaxRootFans restarts, sharing one
  // more search budget.
  if (cur.verification.Score() > 0 && cur.verification.Score() <= kMaxDefectsForPairs &&
      cur.verification.first_defect == 0 && !st.search_budget_exhausted) {
    std::vector<GrowConstraints> fans;
    RootFanEdits(g, grown, lookahead, &fans);
    SearchBudget b = fresh_budget();  // one budget for all restarts together
    for (size_t i = 0; i < fans.size() && i < static_cast<size_t>(kMaxRootFans) && b.evals_left > 0; ++i) {
      FaceRecoveryStats sub = st;
      SearchCandidate c = Repair(g, EvaluateCandidate(g, std::move(fans[i])), lookahead, &b, &sub);
      st.search_evaluations = sub.search_evaluations + 1;
      st.pair_evaluations = sub.pair_evaluations;
      if (c.verification.BetterThan(cur.verification)) cur = std::move(c);
    }
  }
  st.verify_failures = cur.verification.Score();
  if (stats) *stats = st;
  return std::move(cur.faces);
}

StatusOr<std::vector<std::array<int32_t, 3>>> RecoverComponentFaces(const ComponentLayers& layers,
                                                                    FaceRecoveryStats* stats) {
  SILK_ASSIGN_OR_RETURN(ComponentGraph g, BuildComponentGraph(layers));
  return RecoverFacesOfGraph(g, stats);
}

}  // namespace silk
