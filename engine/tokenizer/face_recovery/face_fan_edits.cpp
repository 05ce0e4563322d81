// SPDX-License-Identifier: MIT
// Whole-fan edits of the verification search; see face_fan_edits.h.
#include "tokenizer/face_recovery/face_fan_edits.h"

#include <array>

namespace silk {
namespace {

using Fan = std::vector<int32_t>;  // neighbours in rotation order; closed = last joins first

void PushFan(const ComponentGraph& g, const GrowConstraints& base, int32_t v, const Fan& fan, bool closed,
             bool reversed, int64_t lookahead_budget, std::vector<GrowConstraints>* out) {
  GrowConstraints c = base;
  std::vector<std::array<int32_t, 3>> faces;
  const size_t n = fan.size();
  for (size_t k = 0; k + 1 < n + (closed ? 1 : 0); ++k) {
    const int32_t a = fan[k], b = fan[(k + 1) % n];
    faces.push_back(reversed ? std::array<int32_t, 3>{v, b, a} : std::array<int32_t, 3>{v, a, b});
  }
  c.forced.insert(c.forced.begin(), faces.begin(), faces.end());
  c.forbidden.resize(g.triangles.size(), 0);
  for (int32_t w : g.neighbors[static_cast<size_t>(v)])
    for (int32_t t : g.edge_triangles[static_cast<size_t>(g.EdgeOf(v, w))]) c.forbidden[static_cast<size_t>(t)] = 1;
  for (const auto& f : faces)
    for (int32_t t : g.edge_triangles[static_cast<size_t>(g.EdgeOf(f[0], f[1]))]) {
      const auto& k = g.triangles[static_cast<size_t>(t)];
      if ((k[0] == f[2] || k[1] == f[2] || k[2] == f[2])) c.forbidden[static_cast<size_t>(t)] = 0;
    }
  c.only_forced = false;
  c.lookahead_budget = lookahead_budget;
  out->push_back(std::move(c));
}

}  // namespace

void RootFanEdits(const ComponentGraph& g, const SearchCandidate& from, int64_t lookahead_budget,
                  std::vector<GrowConstraints>* out) {
  // Layer 1 in order is R(root) (§5.2: nothing but the root is visited).
  Fan fan;
  for (int32_t x = g.layer_start[1]; g.layer_start.size() > 2 && x < g.layer_start[2]; ++x) fan.push_back(x);
  if (fan.size() < 2) return;
  for (size_t k = 0; k + 1 < fan.size(); ++k)
    if (g.EdgeOf(fan[k], fan[k + 1]) < 0) return;
  std::vector<std::pair<Fan, bool>> fans{{fan, false}};
  if (fan.size() >= 3 && g.EdgeOf(fan.back(), fan.front()) >= 0) fans.push_back({fan, true});
  const GrowConstraints fresh;
  const bool from_fresh = from.constraints.forced.empty() && from.constraints.forbidden.empty();
  for (const auto& [f, closed] : fans) {
    if (!from_fresh) PushFan(g, from.constraints, 0, f, closed, false, lookahead_budget, out);
    PushFan(g, fresh, 0, f, closed, false, lookahead_budget, out);
  }
}

}  // namespace silk
