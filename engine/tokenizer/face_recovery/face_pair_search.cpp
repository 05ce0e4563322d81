// SPDX-License-Identifier: MIT
// Pairwise step of the verification search; see face_pair_search.h.
#include "tokenizer/face_recovery/face_pair_search.h"

#include <algorithm>
#include <utility>
#include <vector>

namespace silk {
namespace {

// Pairs are tried at this many of the current set's first suspects.
constexpr size_t kFirstVertices = 3;

// Both regrowing edits (face_search_edits.h) on two triangles that share an edge, the first
// at vertex v: e.g. the two faces of one edge replaced at once. Evaluates them, keeps in
// *out the best set strictly better than `cur`.
bool AdjacentPairsAt(const ComponentGraph& g, const SearchCandidate& cur, int32_t v, int64_t lookahead_budget,
                     int32_t* evaluations_left, SearchCandidate* out, bool found) {
  std::vector<int32_t> incident;
  for (int32_t w : g.neighbors[static_cast<size_t>(v)])
    for (int32_t t : g.edge_triangles[static_cast<size_t>(g.EdgeOf(v, w))]) incident.push_back(t);
  std::sort(incident.begin(), incident.end());
  incident.erase(std::unique(incident.begin(), incident.end()), incident.end());
  std::vector<int32_t> partners;
  for (int32_t t1 : incident) {
    // Only pairs with at least one face of cur: two absent triangles change nothing there.
    partners.clear();
    for (int32_t e : g.triangle_edges[static_cast<size_t>(t1)])
      for (int32_t t2 : g.edge_triangles[static_cast<size_t>(e)])
        if (t2 != t1) partners.push_back(t2);
    std::sort(partners.begin(), partners.end());
    partners.erase(std::unique(partners.begin(), partners.end()), partners.end());
    for (int32_t t2 : partners) {
      if (cur.orient[static_cast<size_t>(t1)] == 0 && cur.orient[static_cast<size_t>(t2)] == 0) continue;
      for (int a = 0; a < 2; ++a) {
        for (int b = 0; b < 2; ++b) {
          if (*evaluations_left <= 0) return found;
          --*evaluations_left;
          GrowConstraints c = cur.constraints;
          ApplyRegrowEdit(g, cur, t2, b, &c);
          ApplyRegrowEdit(g, cur, t1, a, &c);
          c.lookahead_budget = lookahead_budget;
          SearchCandidate cand = EvaluateCandidate(g, std::move(c));
          if (cand.verification.BetterThan(found ? out->verification : cur.verification)) {
            *out = std::move(cand);
            found = true;
          }
        }
      }
    }
  }
  return found;
}

}  // namespace

bool FindImprovingPair(const ComponentGraph& g, const SearchCandidate& cur, int64_t lookahead_budget,
                       int32_t* evaluations_left, SearchCandidate* out) {
  const auto& suspects = cur.verification.suspects;
  bool found = false;
  for (size_t i = 0; i < suspects.size() && i < kFirstVertices && !found; ++i)
    found = AdjacentPairsAt(g, cur, suspects[i], lookahead_budget, evaluations_left, out, found);
  return found;
}

}  // namespace silk
