// SPDX-License-Identifier: MIT
// Candidate evaluation and the single edits of the verification search; see face_search_edits.h.
#include "tokenizer/face_recovery/face_search_edits.h"

#include <algorithm>
#include <utility>

namespace silk {
namespace {

std::array<int32_t, 3> Oriented(const ComponentGraph& g, int32_t t, int8_t o) {
  const auto& k = g.triangles[static_cast<size_t>(t)];
  return o > 0 ? std::array<int32_t, 3>{k[0], k[1], k[2]} : std::array<int32_t, 3>{k[0], k[2], k[1]};
}

// `from`'s faces, except triangle `skip`, as a direct edit (no growth).
GrowConstraints Frozen(const ComponentGraph& g, const SearchCandidate& from, int32_t skip) {
  GrowConstraints c;
  for (size_t k = 0; k < from.orient.size(); ++k)
    if (from.orient[k] != 0 && static_cast<int32_t>(k) != skip)
      c.forced.push_back(Oriented(g, static_cast<int32_t>(k), from.orient[k]));
  c.forbidden.assign(g.triangles.size(), 0);
  c.only_forced = true;
  return c;
}

}  // namespace

SearchCandidate EvaluateCandidate(const ComponentGraph& g, GrowConstraints constraints, FaceRecoveryStats* stats) {
  SearchCandidate c;
  c.orient = GrowFaces(g, constraints, stats);
  c.faces = FacesOfOrientation(g, c.orient);
  c.verification = VerifyComponentFaces(g, c.faces);
  c.constraints = std::move(constraints);
  return c;
}

void ApplyRegrowEdit(const ComponentGraph& g, const SearchCandidate& from, int32_t t, int variant, GrowConstraints* c) {
  const int8_t o = from.orient[static_cast<size_t>(t)];
  if (o != 0 && variant == 0) {
    c->forbidden.resize(g.triangles.size(), 0);
    c->forbidden[static_cast<size_t>(t)] = 1;
  } else {
    const int8_t want = o != 0 ? static_cast<int8_t>(-o) : (variant == 0 ? int8_t{1} : int8_t{-1});
    c->forced.insert(c->forced.begin(), Oriented(g, t, want));
    if (!c->forbidden.empty()) c->forbidden[static_cast<size_t>(t)] = 0;
  }
}

void EditsAt(const ComponentGraph& g, const SearchCandidate& from, int32_t v, int64_t lookahead_budget,
             std::vector<GrowConstraints>* out) {
  std::vector<int32_t> incident;
  for (int32_t w : g.neighbors[static_cast<size_t>(v)])
    for (int32_t t : g.edge_triangles[static_cast<size_t>(g.EdgeOf(v, w))]) incident.push_back(t);
  std::sort(incident.begin(), incident.end());
  incident.erase(std::unique(incident.begin(), incident.end()), incident.end());
  for (int32_t t : incident) {
    const int8_t o = from.orient[static_cast<size_t>(t)];
    for (int variant = 0; variant < 4; ++variant) {
      // On a set that is already a direct edit, variants 0 and 1 are direct edits too.
      if (variant >= 2 && from.constraints.only_forced) break;
      if (variant == 3 && o != 0) break;
      GrowConstraints alt;
      if (variant >= 2) {  // drop (present) or add (absent) with nothing else changed
        alt = Frozen(g, from, t);
        if (o != 0) {
          alt.forbidden[static_cast<size_t>(t)] = 1;
        } else {
          alt.forced.push_back(Oriented(g, t, variant == 2 ? int8_t{1} : int8_t{-1}));
        }
      } else {
        alt = from.constraints;
        ApplyRegrowEdit(g, from, t, variant, &alt);
      }
      alt.lookahead_budget = lookahead_budget;
      out->push_back(std::move(alt));
    }
  }
}

}  // namespace silk
