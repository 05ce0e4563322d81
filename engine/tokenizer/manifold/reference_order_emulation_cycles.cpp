// SPDX-License-Identifier: MIT
// networkx simple_cycles on the directed version of an undirected view (token_format.md §14.B.4):
// Tarjan's strongly connected components plus Johnson's search, in the reference's order.
#include <algorithm>

#include "tokenizer/manifold/reference_order_emulation.h"

namespace silk {
namespace refemu {
namespace {

// The DiGraph simple_cycles builds from the arc list; nodes are D-locals.
struct Digraph {
  std::vector<int32_t> name;               // D-local -> node name (for CPython hashing)
  std::vector<int32_t> g_local;            // D-local -> local of the undirected graph
  std::vector<std::vector<int32_t>> succ;  // successor order = undirected adjacency order
  std::vector<char> alive;
  int32_t alive_count = 0;
};

// Iteration order of a CPython set built by inserting the D-locals `seq` in order.
std::vector<int32_t> SetOrder(const Digraph& d, const std::vector<int32_t>& seq) {
  std::vector<int32_t> names;
  for (int32_t x : seq) names.push_back(d.name[static_cast<size_t>(x)]);
  std::vector<int32_t> out;
  for (int32_t nm : PySetOrderInts(names))
    for (int32_t x : seq)
      if (d.name[static_cast<size_t>(x)] == nm) {
        out.push_back(x);
        break;
      }
  return out;
}

// networkx strongly_connected_components (non-recursive Tarjan/Nuutila) over the nodes with
// ok[x] set, sources in `order`. Each component: its set insertion sequence (root first).
std::vector<std::vector<int32_t>> Tarjan(const Digraph& d, const std::vector<int32_t>& order,
                                         const std::vector<char>& ok) {
  const size_t n = d.name.size();
  std::vector<int32_t> preorder(n, 0), lowlink(n, 0);
  std::vector<size_t> it(n, 0);
  std::vector<char> found(n, 0);
  std::vector<int32_t> pending;
  std::vector<std::vector<int32_t>> comps;
  int32_t counter = 0;
  for (int32_t source : order) {
    if (found[static_cast<size_t>(source)]) continue;
    std::vector<int32_t> queue{source};
    while (!queue.empty()) {
      const int32_t v = queue.back();
      const size_t vi = static_cast<size_t>(v);
      if (preorder[vi] == 0) preorder[vi] = ++counter;
      bool done = true;
      const auto& sv = d.succ[vi];
      while (it[vi] < sv.size()) {
        const int32_t w = sv[it[vi]++];
        if (!ok[static_cast<size_t>(w)]) continue;
        if (preorder[static_cast<size_t>(w)] == 0) {
          queue.push_back(w);
          done = false;
          break;
        }
      }
      if (!done) continue;
      lowlink[vi] = preorder[vi];
      for (int32_t w : sv) {
        const size_t wi = static_cast<size_t>(w);
        if (!ok[wi] || found[wi]) continue;
        lowlink[vi] = std::min(lowlink[vi], preorder[wi] > preorder[vi] ? lowlink[wi] : preorder[wi]);
      }
      queue.pop_back();
      if (lowlink[vi] == preorder[vi]) {
        std::vector<int32_t> comp{v};
        while (!pending.empty() && preorder[static_cast<size_t>(pending.back())] > preorder[vi]) {
          comp.push_back(pending.back());
          pending.pop_back();
        }
        for (int32_t x : comp) found[static_cast<size_t>(x)] = 1;
        comps.push_back(std::move(comp));
      } else {
        pending.push_back(v);
      }
    }
  }
  return comps;
}

// _johnson_cycle_search(G restricted to ok, [start]); appends cycles (D-locals) to out.
void Johnson(const Digraph& d, const std::vector<char>& ok, int32_t start, std::vector<std::vector<int32_t>>* out) {
  const size_t n = d.name.size();
  std::vector<std::vector<int32_t>> nbrs(n);
  std::vector<char> cached(n, 0);
  auto succ = [&](int32_t v) -> const std::vector<int32_t>& {
    const size_t vi = static_cast<size_t>(v);
    if (!cached[vi]) {
      cached[vi] = 1;
      for (int32_t w : d.succ[vi])
        if (ok[static_cast<size_t>(w)]) nbrs[vi].push_back(w);
    }
    return nbrs[vi];
  };
  std::vector<char> blocked(n, 0);
  std::vector<std::vector<int32_t>> b(n);
  std::vector<int32_t> path{start};
  blocked[static_cast<size_t>(start)] = 1;
  std::vector<std::pair<int32_t, size_t>> stack{{start, 0}};  // node whose successors we scan, position
  std::vector<char> closed{0};
  while (!stack.empty()) {
    auto& top = stack.back();
    const auto& sv = succ(top.first);
    bool advanced = false;
    while (top.second < sv.size()) {
      const int32_t w = sv[top.second++];
      if (w == start) {
        out->push_back(path);
        closed.back() = 1;
      } else if (!blocked[static_cast<size_t>(w)]) {
        path.push_back(w);
        closed.push_back(0);
        blocked[static_cast<size_t>(w)] = 1;
        stack.emplace_back(w, 0);
        advanced = true;
        break;
      }
    }
    if (advanced) continue;
    stack.pop_back();
    const int32_t v = path.back();
    path.pop_back();
    const bool was_closed = closed.back() != 0;
    closed.pop_back();
    if (was_closed) {
      if (!closed.empty()) closed.back() = 1;
      std::vector<int32_t> work{v};  // unblocking closure: order does not matter
      while (!work.empty()) {
        const int32_t u = work.back();
        work.pop_back();
        const size_t ui = static_cast<size_t>(u);
        if (blocked[ui]) {
          blocked[ui] = 0;
          work.insert(work.end(), b[ui].begin(), b[ui].end());
          b[ui].clear();
        }
      }
    } else {
      for (int32_t w : succ(v)) {
        auto& bw = b[static_cast<size_t>(w)];
        if (std::find(bw.begin(), bw.end(), v) == bw.end()) bw.push_back(v);
      }
    }
  }
}

}  // namespace

std::vector<std::vector<int32_t>> NxSimpleCyclesOfDirectedView(const NxGraph& g,
                                                               const std::vector<int32_t>& view_order) {
  std::vector<char> in_view(static_cast<size_t>(g.size()), 0);
  for (int32_t l : view_order) in_view[static_cast<size_t>(l)] = 1;
  // to_directed() keeps the view's node and adjacency order; simple_cycles then rebuilds a
  // DiGraph from the arc list, so node order = first appearance among the arcs.
  Digraph d;
  std::vector<int32_t> dl(static_cast<size_t>(g.size()), -1);
  auto node = [&](int32_t gl) {
    int32_t& x = dl[static_cast<size_t>(gl)];
    if (x < 0) {
      x = static_cast<int32_t>(d.name.size());
      d.name.push_back(g.label[static_cast<size_t>(gl)]);
      d.g_local.push_back(gl);
      d.succ.emplace_back();
      d.alive.push_back(1);
      ++d.alive_count;
    }
    return x;
  };
  for (int32_t u : view_order)
    for (int32_t v : g.adj[static_cast<size_t>(u)]) {
      if (!in_view[static_cast<size_t>(v)] || v == u) continue;
      const int32_t du = node(u);
      const int32_t dv = node(v);
      d.succ[static_cast<size_t>(du)].push_back(dv);
    }
  const size_t n = d.name.size();

  std::vector<std::vector<int32_t>> out;
  std::vector<int32_t> all(n);
  for (size_t i = 0; i < n; ++i) all[i] = static_cast<int32_t>(i);
  std::vector<std::vector<int32_t>> comps;
  for (auto& c : Tarjan(d, all, d.alive))
    if (c.size() >= 2) comps.push_back(std::move(c));
  std::vector<std::vector<int32_t>> cycles_d;
  while (!comps.empty()) {
    std::vector<int32_t> c = std::move(comps.back());
    comps.pop_back();
    const std::vector<int32_t> c_iter = SetOrder(d, c);  // iteration order of the scc set
    std::vector<char> ok(n, 0);
    for (int32_t x : c)
      if (d.alive[static_cast<size_t>(x)]) ok[static_cast<size_t>(x)] = 1;
    const int32_t v = c_iter.front();
    Johnson(d, ok, v, &cycles_d);
    d.alive[static_cast<size_t>(v)] = 0;
    --d.alive_count;
    ok[static_cast<size_t>(v)] = 0;
    // Node order of the subgraph view G.subgraph(c) after v left G (token_format.md §14.B.3).
    std::vector<int32_t> order;
    if (2 * static_cast<int64_t>(c.size()) < d.alive_count) {
      for (int32_t x : SetOrder(d, c_iter))
        if (ok[static_cast<size_t>(x)]) order.push_back(x);
    } else {
      for (size_t x = 0; x < n; ++x)
        if (ok[x]) order.push_back(static_cast<int32_t>(x));
    }
    for (auto& c2 : Tarjan(d, order, ok))
      if (c2.size() >= 2) comps.push_back(std::move(c2));
  }
  for (auto& cyc : cycles_d) {
    std::vector<int32_t> gl;
    for (int32_t x : cyc) gl.push_back(d.g_local[static_cast<size_t>(x)]);
    out.push_back(std::move(gl));
  }
  return out;
}

}  // namespace refemu
}  // namespace silk
