// SPDX-License-Identifier: MIT
// CPython set order and networkx Graph orders (token_format.md §14.B.1-§14.B.3), reproduced from the
// recipes of the spec so the non-manifold pass partitions faces exactly like the reference.
#include "tokenizer/manifold/reference_order_emulation.h"

#include <algorithm>

namespace silk {
namespace refemu {
namespace {

constexpr uint64_t kXXPrime1 = 11400714785074694791ULL;
constexpr uint64_t kXXPrime2 = 14029467366897019727ULL;
constexpr uint64_t kXXPrime5 = 2870177450012600261ULL;

// CPython set table with open addressing (setobject.c: set_add_entry / set_table_resize).
// Keys are identified by `key`, placed by `hash`; returns indices into the input of the
// distinct keys, in iteration order.
std::vector<int32_t> PySetOrderIndices(const std::vector<uint64_t>& hashes, const std::vector<uint64_t>& keys) {
  constexpr size_t kLinearProbes = 9;
  size_t mask = 7;
  std::vector<int32_t> table(8, -1);  // slot -> input index of the stored key
  size_t used = 0;

  auto probe_insert = [&](std::vector<int32_t>& tab, size_t msk, int32_t idx, bool check_dup) -> bool {
    const uint64_t h = hashes[static_cast<size_t>(idx)];
    size_t i = static_cast<size_t>(h) & msk;
    uint64_t perturb = h;
    while (true) {
      const size_t probes = (i + kLinearProbes <= msk) ? kLinearProbes : 0;
      for (size_t j = 0; j <= probes; ++j) {
        const int32_t s = tab[i + j];
        if (s < 0) {
          tab[i + j] = idx;
          return true;
        }
        if (check_dup && keys[static_cast<size_t>(s)] == keys[static_cast<size_t>(idx)]) return false;
      }
      perturb >>= 5;
      i = (i * 5 + 1 + static_cast<size_t>(perturb)) & msk;
    }
  };

  for (size_t n = 0; n < keys.size(); ++n) {
    if (!probe_insert(table, mask, static_cast<int32_t>(n), true)) continue;
    ++used;
    if (used * 5 < mask * 3) continue;
    size_t new_size = 8;
    while (new_size <= used * 4) new_size <<= 1;
    std::vector<int32_t> grown(new_size, -1);
    for (int32_t s : table)
      if (s >= 0) probe_insert(grown, new_size - 1, s, false);
    table.swap(grown);
    mask = new_size - 1;
  }
  std::vector<int32_t> order;
  order.reserve(used);
  for (int32_t s : table)
    if (s >= 0) order.push_back(s);
  return order;
}

}  // namespace

uint64_t PyHashIntPair(int64_t a, int64_t b) {
  uint64_t acc = kXXPrime5;
  for (int64_t t : {a, b}) {
    acc += PyHashInt(t) * kXXPrime2;
    acc = (acc << 31) | (acc >> 33);
    acc *= kXXPrime1;
  }
  acc += 2ULL ^ (kXXPrime5 ^ 3527539ULL);
  if (acc == ~0ULL) acc = 1546275796ULL;
  return acc;
}

std::vector<int32_t> PySetOrderInts(const std::vector<int32_t>& seq) {
  std::vector<uint64_t> hashes(seq.size()), keys(seq.size());
  for (size_t i = 0; i < seq.size(); ++i) hashes[i] = keys[i] = PyHashInt(seq[i]);
  std::vector<int32_t> out;
  for (int32_t idx : PySetOrderIndices(hashes, keys)) out.push_back(seq[static_cast<size_t>(idx)]);
  return out;
}

std::vector<std::pair<int32_t, int32_t>> PySetOrderPairs(const std::vector<std::pair<int32_t, int32_t>>& seq) {
  std::vector<uint64_t> hashes(seq.size()), keys(seq.size());
  for (size_t i = 0; i < seq.size(); ++i) {
    hashes[i] = PyHashIntPair(seq[i].first, seq[i].second);
    keys[i] = (static_cast<uint64_t>(static_cast<uint32_t>(seq[i].first)) << 32) | static_cast<uint32_t>(seq[i].second);
  }
  std::vector<std::pair<int32_t, int32_t>> out;
  for (int32_t idx : PySetOrderIndices(hashes, keys)) out.push_back(seq[static_cast<size_t>(idx)]);
  return out;
}

// ---- NxGraph ----

int32_t NxGraph::Find(int32_t name) const {
  for (int32_t i = 0; i < size(); ++i)
    if (label[static_cast<size_t>(i)] == name && alive[static_cast<size_t>(i)]) return i;
  return -1;
}

int32_t NxGraph::AddNode(int32_t name) {
  const int32_t f = Find(name);
  if (f >= 0) return f;
  label.push_back(name);
  adj.emplace_back();
  alive.push_back(1);
  ++alive_count;
  return size() - 1;
}

void NxGraph::AddEdge(int32_t a_name, int32_t b_name) {
  const int32_t a = AddNode(a_name);
  const int32_t b = AddNode(b_name);
  auto& la = adj[static_cast<size_t>(a)];
  if (std::find(la.begin(), la.end(), b) == la.end()) la.push_back(b);  // dict key kept in place
  auto& lb = adj[static_cast<size_t>(b)];
  if (std::find(lb.begin(), lb.end(), a) == lb.end()) lb.push_back(a);
}

void NxGraph::RemoveNode(int32_t local) {
  if (!alive[static_cast<size_t>(local)]) return;
  alive[static_cast<size_t>(local)] = 0;
  --alive_count;
  for (int32_t w : adj[static_cast<size_t>(local)]) {
    auto& lw = adj[static_cast<size_t>(w)];
    lw.erase(std::remove(lw.begin(), lw.end(), local), lw.end());
  }
  adj[static_cast<size_t>(local)].clear();
}

NxGraph NxFromEdges(const std::vector<std::pair<int32_t, int32_t>>& edges) {
  NxGraph g;
  for (const auto& e : edges) g.AddEdge(e.first, e.second);
  return g;
}

NxGraph NxCopy(const NxGraph& g) {
  // Graph.copy(): add_nodes_from(node order), then add_edges_from((u, v) for u in nodes for v
  // in adj(u)); an existing dict entry keeps its position.
  NxGraph c;
  std::vector<int32_t> map(static_cast<size_t>(g.size()), -1);
  for (int32_t u = 0; u < g.size(); ++u)
    if (g.alive[static_cast<size_t>(u)]) map[static_cast<size_t>(u)] = c.AddNode(g.label[static_cast<size_t>(u)]);
  for (int32_t u = 0; u < g.size(); ++u) {
    if (!g.alive[static_cast<size_t>(u)]) continue;
    for (int32_t w : g.adj[static_cast<size_t>(u)])
      c.AddEdge(g.label[static_cast<size_t>(u)], g.label[static_cast<size_t>(w)]);
  }
  return c;
}

NxNodeSet NxSetOrder(const NxGraph& g, const std::vector<int32_t>& locals) {
  std::vector<int32_t> names;
  names.reserve(locals.size());
  for (int32_t l : locals) names.push_back(g.label[static_cast<size_t>(l)]);
  std::vector<int32_t> order = PySetOrderInts(names);
  NxNodeSet out;
  out.reserve(order.size());
  for (int32_t name : order) out.push_back(g.Find(name));
  return out;
}

std::vector<NxNodeSet> NxConnectedComponents(const NxGraph& g) {
  // connected_components / _plain_bfs: level-by-level BFS; the set is filled with the
  // source, then nodes in discovery order.
  std::vector<NxNodeSet> comps;
  std::vector<char> seen(static_cast<size_t>(g.size()), 0);
  for (int32_t s = 0; s < g.size(); ++s) {
    if (!g.alive[static_cast<size_t>(s)] || seen[static_cast<size_t>(s)]) continue;
    std::vector<int32_t> found{s};
    seen[static_cast<size_t>(s)] = 1;
    for (size_t k = 0; k < found.size(); ++k)
      for (int32_t w : g.adj[static_cast<size_t>(found[k])])
        if (!seen[static_cast<size_t>(w)]) {
          seen[static_cast<size_t>(w)] = 1;
          found.push_back(w);
        }
    comps.push_back(NxSetOrder(g, found));
  }
  return comps;
}

std::vector<std::pair<int32_t, int32_t>> NxEdges(const NxGraph& g, const std::vector<int32_t>& nbunch) {
  std::vector<std::pair<int32_t, int32_t>> out;
  std::vector<char> done(static_cast<size_t>(g.size()), 0);
  for (int32_t n : nbunch) {
    if (n < 0 || !g.alive[static_cast<size_t>(n)] || done[static_cast<size_t>(n)]) continue;
    for (int32_t m : g.adj[static_cast<size_t>(n)])
      if (!done[static_cast<size_t>(m)]) out.emplace_back(n, m);
    done[static_cast<size_t>(n)] = 1;
  }
  return out;
}

std::vector<int32_t> NxSubgraphNodeOrder(const NxGraph& g, const NxNodeSet& set_order) {
  // subgraph(S) filters with show_nodes(set(S)); FilterAtlas iterates that new set when it
  // is less than half the graph, else the graph's node dict.
  std::vector<int32_t> out;
  if (2 * static_cast<int64_t>(set_order.size()) < g.alive_count) {
    for (int32_t l : NxSetOrder(g, set_order))
      if (g.alive[static_cast<size_t>(l)]) out.push_back(l);
    return out;
  }
  std::vector<char> in(static_cast<size_t>(g.size()), 0);
  for (int32_t l : set_order) in[static_cast<size_t>(l)] = 1;
  for (int32_t u = 0; u < g.size(); ++u)
    if (g.alive[static_cast<size_t>(u)] && in[static_cast<size_t>(u)]) out.push_back(u);
  return out;
}

std::vector<int32_t> NxLongestTreePath(const NxGraph& g, const std::vector<int32_t>& view_order) {
  std::vector<char> in(static_cast<size_t>(g.size()), 0);
  for (int32_t l : view_order) in[static_cast<size_t>(l)] = 1;
  std::vector<int32_t> best;
  std::vector<int32_t> parent(static_cast<size_t>(g.size()), -1), depth(static_cast<size_t>(g.size()), 0);
  std::vector<char> seen(static_cast<size_t>(g.size()), 0);
  for (int32_t src : view_order) {
    // Unit-weight Dijkstra pops in (distance, push count) order = FIFO BFS.
    std::fill(seen.begin(), seen.end(), 0);
    std::vector<int32_t> found{src};
    seen[static_cast<size_t>(src)] = 1;
    parent[static_cast<size_t>(src)] = -1;
    depth[static_cast<size_t>(src)] = 1;
    for (size_t k = 0; k < found.size(); ++k) {
      const int32_t v = found[k];
      for (int32_t w : g.adj[static_cast<size_t>(v)]) {
        if (!in[static_cast<size_t>(w)] || seen[static_cast<size_t>(w)]) continue;
        seen[static_cast<size_t>(w)] = 1;
        parent[static_cast<size_t>(w)] = v;
        depth[static_cast<size_t>(w)] = depth[static_cast<size_t>(v)] + 1;
        found.push_back(w);
      }
    }
    for (int32_t t : found) {
      if (depth[static_cast<size_t>(t)] <= static_cast<int32_t>(best.size())) continue;
      best.assign(static_cast<size_t>(depth[static_cast<size_t>(t)]), 0);
      int32_t x = t;
      for (size_t i = best.size(); i-- > 0;) {
        best[i] = x;
        x = parent[static_cast<size_t>(x)];
      }
    }
  }
  return best;
}

}  // namespace refemu
}  // namespace silk
