// Face recovery = growth (face_growth) + exact verification (face_verification) + a bounded
// local search that repairs the growth's answer where the replayed layering disagrees.
#include "tokenizer/face_recovery.h"

#include <algorithm>
#include <utility>

#include "tokenizer/face_growth.h"
#include "tokenizer/face_verification.h"

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

struct Candidate {
  GrowConstraints constraints;
  std::vector<int8_t> orient;
  std::vector<std::array<int32_t, 3>> faces;
  FaceVerification verification;
};

Candidate Evaluate(const ComponentGraph& g, GrowConstraints constraints, FaceRecoveryStats* stats) {
  Candidate c;
  c.orient = GrowFaces(g, constraints, stats);
  c.faces = FacesOfOrientation(g, c.orient);
  c.verification = VerifyComponentFaces(g, c.faces);
  c.constraints = std::move(constraints);
  return c;
}

std::array<int32_t, 3> Oriented(const ComponentGraph& g, int32_t t, int8_t o) {
  const auto& k = g.triangles[static_cast<size_t>(t)];
  return o > 0 ? std::array<int32_t, 3>{k[0], k[1], k[2]} : std::array<int32_t, 3>{k[0], k[2], k[1]};
}

}  // namespace

StatusOr<std::vector<std::array<int32_t, 3>>> RecoverFacesOfGraph(const ComponentGraph& g,
                                                                   FaceRecoveryStats* stats) {
  FaceRecoveryStats st;
  Candidate cur = Evaluate(g, {}, &st);
  const int64_t unit = static_cast<int64_t>(g.triangles.size() + g.edges.size()) + g.vertex_count + 1;
  const int32_t max_evals = static_cast<int32_t>(std::min<int64_t>(kMaxEvaluations, kSearchWork / unit));
  const size_t tri_count = g.triangles.size();
  std::vector<char> exhausted(static_cast<size_t>(g.vertex_count), 0);
  std::vector<int32_t> seen(tri_count, -1), incident;
  int32_t evals = 0, round = 0;
  if (cur.verification.Score() > std::max(kMaxDefectsToRepair, g.vertex_count / kVerticesPerRepairableDefect))
    st.search_budget_exhausted = true;
  while (cur.verification.Score() > 0 && !st.search_budget_exhausted) {
    int32_t focus = -1;
    for (int32_t v : cur.verification.suspects) {
      if (!exhausted[static_cast<size_t>(v)]) {
        focus = v;
        break;
      }
    }
    if (focus < 0) break;
    ++round;
    incident.clear();
    for (int32_t w : g.neighbors[static_cast<size_t>(focus)]) {
      for (int32_t t : g.edge_triangles[static_cast<size_t>(g.EdgeOf(focus, w))]) {
        if (seen[static_cast<size_t>(t)] == round) continue;
        seen[static_cast<size_t>(t)] = round;
        incident.push_back(t);
      }
    }
    // One change at the focus vertex, the growth redoes the rest: drop or flip a face it
    // has (or drop it with no regrowth), or impose a face it lacks in either winding. A change is kept when it removes a
    // defect or moves the first defect later at the same count (a strict, well-founded
    // order, so the search cannot cycle).
    Candidate best;
    bool have_best = false;
    for (int32_t t : incident) {
      for (int variant = 0; variant < 3; ++variant) {
        if (evals >= max_evals) {
          st.search_budget_exhausted = true;
          break;
        }
        GrowConstraints alt = cur.constraints;
        alt.lookahead_budget = kSearchLookAheadPerUnit * unit;
        const int8_t o = cur.orient[static_cast<size_t>(t)];
        if (variant == 2 && (o == 0 || cur.constraints.only_forced)) continue;
        if (variant == 2) {  // drop the face and change nothing else (a hole the growth would refill)
          alt.forced.clear();
          for (size_t k = 0; k < tri_count; ++k)
            if (cur.orient[k] != 0 && static_cast<int32_t>(k) != t) alt.forced.push_back(Oriented(g, static_cast<int32_t>(k), cur.orient[k]));
          alt.forbidden.assign(tri_count, 0);
          alt.forbidden[static_cast<size_t>(t)] = 1;
          alt.only_forced = true;
        } else if (o != 0 && variant == 0) {
          alt.forbidden.resize(tri_count, 0);
          alt.forbidden[static_cast<size_t>(t)] = 1;
        } else {
          const int8_t want = o != 0 ? static_cast<int8_t>(-o) : (variant == 0 ? int8_t{1} : int8_t{-1});
          alt.forced.insert(alt.forced.begin(), Oriented(g, t, want));
          if (!alt.forbidden.empty()) alt.forbidden[static_cast<size_t>(t)] = 0;
        }
        ++evals;
        Candidate c = Evaluate(g, std::move(alt), nullptr);
        if (c.verification.BetterThan(have_best ? best.verification : cur.verification)) {
          best = std::move(c);
          have_best = true;
        }
      }
      if (st.search_budget_exhausted) break;
    }
    if (have_best) {
      cur = std::move(best);
      std::fill(exhausted.begin(), exhausted.end(), 0);
    } else {
      exhausted[static_cast<size_t>(focus)] = 1;
    }
  }
  st.verify_failures = cur.verification.Score();
  st.search_evaluations = evals;
  if (stats) *stats = st;
  return std::move(cur.faces);
}

StatusOr<std::vector<std::array<int32_t, 3>>> RecoverComponentFaces(const ComponentLayers& layers,
                                                                     FaceRecoveryStats* stats) {
  SILK_ASSIGN_OR_RETURN(ComponentGraph g, BuildComponentGraph(layers));
  return RecoverFacesOfGraph(g, stats);
}

}  // namespace silk
