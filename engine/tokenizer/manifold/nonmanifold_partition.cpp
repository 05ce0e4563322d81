// SPDX-License-Identifier: MIT
// PARTITION(v) (token_format.md §3.4): cycles and chains are peeled off the edge graph of v in the
// reference's order; leftover edges become single-face groups. Orders come from refemu.
#include "tokenizer/manifold/nonmanifold_partition.h"

#include <algorithm>
#include <string>
#include <utility>

#include "tokenizer/manifold/reference_order_emulation.h"
#include "tokenizer/refusal.h"
#include "tokenizer/manifold/vertex_edge_graph.h"

namespace silk {
namespace {

using Key = std::pair<int32_t, int32_t>;

Key MakeKey(int32_t a, int32_t b) { return a < b ? Key(a, b) : Key(b, a); }

// Keys of the consecutive node pairs of `nodes` (names), closing the loop if `cyclic`.
std::vector<Key> PathKeys(const refemu::NxGraph& g, const std::vector<int32_t>& nodes, bool cyclic) {
  std::vector<Key> out;
  const size_t n = nodes.size();
  const size_t m = cyclic ? n : (n == 0 ? 0 : n - 1);
  for (size_t i = 0; i < m; ++i)
    out.push_back(MakeKey(g.label[static_cast<size_t>(nodes[i])], g.label[static_cast<size_t>(nodes[(i + 1) % n])]));
  return out;
}

// Orig.edges(nbunch) as keys.
std::vector<Key> EdgeKeys(const refemu::NxGraph& g, const std::vector<int32_t>& nbunch) {
  std::vector<Key> out;
  for (const auto& e : refemu::NxEdges(g, nbunch))
    out.push_back(MakeKey(g.label[static_cast<size_t>(e.first)], g.label[static_cast<size_t>(e.second)]));
  return out;
}

bool Contains(const std::vector<Key>& v, const Key& k) { return std::find(v.begin(), v.end(), k) != v.end(); }

int32_t EdgeCount(const refemu::NxGraph& g, const std::vector<int32_t>& comp) {
  size_t deg = 0;
  for (int32_t l : comp) deg += g.adj[static_cast<size_t>(l)].size();
  return static_cast<int32_t>(deg / 2);
}

// SELECT_CYCLE (max_cycle_rule): fewest distinct face-component roots, then longest, then first.
Status SelectCycle(const refemu::NxGraph& g, const std::vector<int32_t>& view, const VertexEdgeGraph& eg,
                   const std::vector<int32_t>& face_cc, UnionFind& uf, std::vector<int32_t>* chosen) {
  std::vector<std::vector<int32_t>> cycles;
  for (auto& c : refemu::NxSimpleCyclesOfDirectedView(g, view))
    if (c.size() != 2) cycles.push_back(std::move(c));
  if (cycles.empty()) return Refuse(Refusal::kNonManifoldWrong, "can not find cycle");
  if (cycles.size() == 1) {
    *chosen = cycles[0];
    return Status::Ok();
  }
  size_t best = 0;
  int32_t best_cc = 1000;
  size_t best_len = 0;
  for (size_t i = 0; i < cycles.size(); ++i) {
    std::vector<int32_t> roots;
    for (const Key& k : PathKeys(g, cycles[i], true)) {
      const int32_t cc = face_cc[static_cast<size_t>(eg.FaceOf(k.first, k.second))];
      if (cc == -1) continue;
      const int32_t r = uf.Find(cc);
      if (std::find(roots.begin(), roots.end(), r) == roots.end()) roots.push_back(r);
    }
    const int32_t cnt = static_cast<int32_t>(roots.size());
    if (cnt < best_cc) {
      best_cc = cnt;
      best = i;
      best_len = cycles[i].size();
    }
    if (cnt == best_cc && cycles[i].size() > best_len) {
      best = i;
      best_len = cycles[i].size();
    }
  }
  *chosen = cycles[best];
  return Status::Ok();
}

// Cycles and chains (tree paths) as node lists, in the order they are peeled off the graph.
struct PeeledFan {
  std::vector<std::vector<int32_t>> cycles, chains;
};

// Peels components off `g` until none is left: a tree gives up its longest path (a chain), any
// other component a cycle chosen by SELECT_CYCLE; single nodes are dropped.
Status PeelCyclesAndChains(refemu::NxGraph& g, const VertexEdgeGraph& eg, const std::vector<int32_t>& face_cc,
                           UnionFind& uf, PeeledFan* peeled) {
  while (g.alive_count > 0) {
    for (const refemu::NxNodeSet& comp : refemu::NxConnectedComponents(g)) {
      if (comp.size() == 1) {
        g.RemoveNode(comp[0]);
        continue;
      }
      const std::vector<int32_t> view = refemu::NxSubgraphNodeOrder(g, comp);
      std::vector<int32_t> picked;
      if (EdgeCount(g, comp) == static_cast<int32_t>(comp.size()) - 1) {
        picked = refemu::NxLongestTreePath(g, view);
        peeled->chains.push_back(picked);
      } else {
        SILK_RETURN_IF_ERROR(SelectCycle(g, view, eg, face_cc, uf, &picked));
        peeled->cycles.push_back(picked);
      }
      for (int32_t l : picked) g.RemoveNode(l);
    }
  }
  return Status::Ok();
}

// Edge groups of the peeled fan, in the reference's order, plus the edges no cycle or chain
// claims (out_c from cycles, out_p from chains).
struct KeyGroups {
  std::vector<std::vector<Key>> groups;
  std::vector<Key> out_c, out_p;
};

// Per cycle: its edges (all of them when it has no extra edge), then each chord as its own
// group; other edges at its nodes go to out_c.
void AddCycleGroups(const refemu::NxGraph& orig, const std::vector<std::vector<int32_t>>& cycles, KeyGroups* kg) {
  for (const auto& k_nodes : cycles) {
    const std::vector<Key> incident_keys = EdgeKeys(orig, k_nodes);
    if (incident_keys.size() == k_nodes.size()) {
      kg->groups.push_back(incident_keys);
      continue;
    }
    const std::vector<Key> cycle_keys = PathKeys(orig, k_nodes, true);
    kg->groups.push_back(cycle_keys);
    auto in_cycle = [&](int32_t name) {
      for (int32_t l : k_nodes)
        if (orig.label[static_cast<size_t>(l)] == name) return true;
      return false;
    };
    for (const Key& e : incident_keys) {
      if (Contains(cycle_keys, e)) continue;
      if (in_cycle(e.first) && in_cycle(e.second))
        kg->groups.push_back({e});  // chord
      else
        kg->out_c.push_back(e);
    }
  }
}

// Per chain: its path edges plus, at each end, the first other edge there (claimed from the
// leftovers). Edges at chain nodes off the paths first go to out_p.
void AddChainGroups(const refemu::NxGraph& orig, const std::vector<std::vector<int32_t>>& chains, KeyGroups* kg) {
  for (const auto& p : chains) {
    const std::vector<Key> path_keys = PathKeys(orig, p, false);
    for (const Key& e : EdgeKeys(orig, p))
      if (!Contains(path_keys, e)) kg->out_p.push_back(e);
  }
  for (const auto& p : chains) {
    std::vector<Key> grp = PathKeys(orig, p, false);
    const std::vector<Key> path_keys = grp;
    for (int32_t end : {p.front(), p.back()}) {
      for (const Key& e : EdgeKeys(orig, {end})) {
        if (Contains(path_keys, e)) continue;
        grp.push_back(e);
        kg->out_p.erase(std::remove(kg->out_p.begin(), kg->out_p.end(), e), kg->out_p.end());
        kg->out_c.erase(std::remove(kg->out_c.begin(), kg->out_c.end(), e), kg->out_c.end());
        break;
      }
    }
    kg->groups.push_back(std::move(grp));
  }
}

// Leftover edges (out_c, then out_p) become single-face groups in Python set order.
void AddLeftoverGroups(KeyGroups* kg) {
  std::vector<Key> leftovers = kg->out_c;
  leftovers.insert(leftovers.end(), kg->out_p.begin(), kg->out_p.end());
  for (const Key& e : refemu::PySetOrderPairs(leftovers)) kg->groups.push_back({e});
}

// The edge groups as face groups; refuses unless they hold every face of v exactly once.
Status FaceGroupsCoveringOnce(const std::vector<std::vector<Key>>& key_groups, const VertexEdgeGraph& eg, int32_t v,
                              std::vector<std::vector<FaceId>>* groups) {
  groups->clear();
  std::vector<int32_t> all;
  for (const auto& kg : key_groups) {
    std::vector<FaceId> fg;
    for (const Key& k : kg) {
      const int32_t f = eg.FaceOf(k.first, k.second);
      fg.emplace_back(f);
      all.push_back(f);
    }
    groups->push_back(std::move(fg));
  }
  std::sort(all.begin(), all.end());
  const bool distinct = std::adjacent_find(all.begin(), all.end()) == all.end();
  if (groups->empty() || !distinct || all.size() != eg.keys.size())
    return Refuse(Refusal::kNonManifoldWrong,
                  "vertex " + std::to_string(v) + ": fan groups do not cover its faces once");
  return Status::Ok();
}

}  // namespace

Status PartitionNonManifoldFan(const std::vector<std::array<int32_t, 3>>& faces, int32_t v,
                               const std::vector<int32_t>& incident, const std::vector<int32_t>& face_cc, UnionFind& uf,
                               std::vector<std::vector<FaceId>>* groups) {
  const VertexEdgeGraph eg = BuildVertexEdgeGraph(faces, v, incident.data(), incident.size());
  refemu::NxGraph g = refemu::NxFromEdges(eg.keys);
  const refemu::NxGraph orig = refemu::NxCopy(g);  // same locals: g has no removed nodes yet
  PeeledFan peeled;                                // locals (valid in g and orig)
  SILK_RETURN_IF_ERROR(PeelCyclesAndChains(g, eg, face_cc, uf, &peeled));
  KeyGroups kg;
  AddCycleGroups(orig, peeled.cycles, &kg);
  AddChainGroups(orig, peeled.chains, &kg);
  AddLeftoverGroups(&kg);
  return FaceGroupsCoveringOnce(kg.groups, eg, v, groups);
}

}  // namespace silk
