// SPDX-License-Identifier: MIT
// Emulation of the reference's incidental iteration orders (token_format.md §14.B): CPython set order and
// the networkx graph orders the non-manifold pass depends on. All such emulation lives here.
#pragma once
#include <cstdint>
#include <utility>
#include <vector>

namespace silk {
namespace refemu {

// ---- CPython (3.8-3.12, 64-bit) hashing and set iteration order (token_format.md §14.B.1) ----

// hash(k) for an integer 0 <= k < 2^61-1 (it is k itself).
inline uint64_t PyHashInt(int64_t k) { return static_cast<uint64_t>(k); }
// hash((a, b)) for two such integers (xxHash-based tuple hash).
uint64_t PyHashIntPair(int64_t a, int64_t b);

// Iteration order of a CPython set built by inserting `seq` element by element.
std::vector<int32_t> PySetOrderInts(const std::vector<int32_t>& seq);
std::vector<std::pair<int32_t, int32_t>> PySetOrderPairs(const std::vector<std::pair<int32_t, int32_t>>& seq);

// ---- networkx Graph (undirected, insertion-ordered dict-of-dicts; token_format.md §14.B.2) ----

// Nodes are addressed by a local index (order of first insertion); `label` is the node's
// integer name in the reference (a vertex id), which is what CPython hashes.
struct NxGraph {
  std::vector<int32_t> label;             // local -> node name
  std::vector<std::vector<int32_t>> adj;  // local -> neighbours in insertion order
  std::vector<char> alive;                // removed nodes keep their slot
  int32_t alive_count = 0;

  int32_t Find(int32_t name) const;              // local index or -1
  int32_t AddNode(int32_t name);                 // existing or new local index
  void AddEdge(int32_t a_name, int32_t b_name);  // Graph.add_edge semantics
  void RemoveNode(int32_t local);                // Graph.remove_node (keeps others' order)
  int32_t size() const { return static_cast<int32_t>(label.size()); }
};

// Graph.add_edges_from(edges) on an empty graph.
NxGraph NxFromEdges(const std::vector<std::pair<int32_t, int32_t>>& edges);
// Graph.copy(): same node order, adjacency rebuilt edge by edge (token_format.md §3.4 "Orig").
NxGraph NxCopy(const NxGraph& g);

// One connected component as networkx returns it: a set of nodes (locals), given here in
// its CPython iteration order.
using NxNodeSet = std::vector<int32_t>;
// nx.connected_components(g) over alive nodes, in networkx order.
std::vector<NxNodeSet> NxConnectedComponents(const NxGraph& g);
// CPython iteration order of a set built by inserting `locals` (by their names) in order.
NxNodeSet NxSetOrder(const NxGraph& g, const std::vector<int32_t>& locals);
// g.edges(nbunch) for nbunch iterated in the given order: (n, m) local pairs.
std::vector<std::pair<int32_t, int32_t>> NxEdges(const NxGraph& g, const std::vector<int32_t>& nbunch);
// Node order of g.subgraph(S) where S is a set iterated as `set_order` (token_format.md §14.B.3),
// evaluated against g's current alive node count.
std::vector<int32_t> NxSubgraphNodeOrder(const NxGraph& g, const NxNodeSet& set_order);

// LONGEST_PATH (token_format.md §3.4): first strictly longest BFS-tree path over sources in
// `view_order`, inside the tree induced by `view_order` (single_source_dijkstra_path).
std::vector<int32_t> NxLongestTreePath(const NxGraph& g, const std::vector<int32_t>& view_order);

// nx.simple_cycles(view.to_directed()) where view = g restricted to `view_order` (its node
// order, token_format.md §14.B.4). Cycles as lists of locals, in networkx order (2-cycles included).
std::vector<std::vector<int32_t>> NxSimpleCyclesOfDirectedView(const NxGraph& g,
                                                               const std::vector<int32_t>& view_order);

}  // namespace refemu
}  // namespace silk
