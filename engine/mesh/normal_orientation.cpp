// SPDX-License-Identifier: MIT
// Minimum spanning forest over the kNN graph (Boruvka rounds with a union-find) and the sign
// propagation from each tree's outward seed.
#include "mesh/normal_orientation.h"

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <numeric>

namespace silk {

namespace {

double Dot(const Point3& a, const Point3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

struct Edge {
  double weight;
  int32_t a, b;  // a < b
  bool operator<(const Edge& o) const {
    return weight < o.weight || (weight == o.weight && (a < o.a || (a == o.a && b < o.b)));
  }
};

// Graph slot i * k + s (point i's s-th neighbour) as an edge: a total order on edges, so the
// minimum spanning forest is unique whichever algorithm finds it.
Edge EdgeOf(const KnnGraph& graph, const std::vector<Point3>& normals, int64_t slot) {
  const int32_t i = static_cast<int32_t>(slot / graph.k), j = graph.neighbors[static_cast<size_t>(slot)];
  const int32_t a = std::min(i, j), b = std::max(i, j);
  return {1 - std::fabs(Dot(normals[a], normals[b])), a, b};
}

int32_t Find(std::vector<int32_t>* parent, int32_t x) {
  std::vector<int32_t>& p = *parent;
  while (p[x] != x) x = p[x] = p[p[x]];
  return x;
}

// The forest as adjacency lists (CSR: offsets n + 1, targets).
struct Forest {
  std::vector<int32_t> offset, target;
};

// One Boruvka round: each tree's lightest edge to another tree (a = -1: none), then those
// joined. Returns the number of edges added to *kept.
StatusOr<int64_t> BoruvkaRound(const KnnGraph& graph, const std::vector<Point3>& normals, std::vector<int32_t>* parent,
                               std::vector<Edge>* best, std::vector<Edge>* kept, const CancelCheck& cancel) {
  const size_t n = normals.size();
  std::fill(best->begin(), best->end(), Edge{0, -1, -1});
  for (size_t i = 0; i < n; ++i) {
    if ((i + 1) % kCancelPollInterval == 0 && CancelRequested(cancel)) return CancelledStatus("normal orientation");
    const int32_t ri = Find(parent, static_cast<int32_t>(i));
    for (int32_t s = 0; s < graph.k; ++s) {
      const int64_t slot = static_cast<int64_t>(i) * graph.k + s;
      const int32_t rj = Find(parent, graph.Of(i)[s]);
      if (ri == rj) continue;
      const Edge e = EdgeOf(graph, normals, slot);
      for (int32_t r : {ri, rj})
        if ((*best)[r].a < 0 || e < (*best)[r]) (*best)[r] = e;
    }
  }
  int64_t added = 0;
  for (size_t r = 0; r < n; ++r) {
    if ((*best)[r].a < 0) continue;
    const Edge e = (*best)[r];
    const int32_t ra = Find(parent, e.a), rb = Find(parent, e.b);
    if (ra == rb) continue;  // the same edge chosen by both of its trees
    (*parent)[std::max(ra, rb)] = std::min(ra, rb);
    kept->push_back(e);
    ++added;
  }
  return added;
}

// The minimum spanning forest of the kNN graph by Boruvka's rounds (each at least halves the
// trees; no list of all n * k edges is held), its edges then in Kruskal's order (by weight, ties
// by index), so the forest's adjacency lists are those Kruskal would build.
StatusOr<Forest> SpanningForest(const KnnGraph& graph, const std::vector<Point3>& normals, const CancelCheck& cancel) {
  const size_t n = normals.size();
  std::vector<int32_t> parent(n);
  std::iota(parent.begin(), parent.end(), 0);
  std::vector<Edge> kept;
  {
    std::vector<Edge> best(n);
    for (;;) {
      SILK_ASSIGN_OR_RETURN(const int64_t added, BoruvkaRound(graph, normals, &parent, &best, &kept, cancel));
      if (added == 0) break;
    }
  }
  std::vector<int32_t>().swap(parent);
  std::sort(kept.begin(), kept.end());
  Forest f;
  f.offset.assign(n + 1, 0);
  for (const Edge& e : kept) ++f.offset[e.a + 1], ++f.offset[e.b + 1];
  for (size_t i = 0; i < n; ++i) f.offset[i + 1] += f.offset[i];
  f.target.resize(kept.size() * 2);
  std::vector<int32_t> fill(f.offset.begin(), f.offset.end() - 1);
  for (const Edge& e : kept) f.target[fill[e.a]++] = e.b, f.target[fill[e.b]++] = e.a;
  return f;
}

// Breadth-first order of the tree holding `root`, marking `seen`.
void TreeOrder(const Forest& f, int32_t root, std::vector<char>* seen, std::vector<int32_t>* order,
               std::vector<int32_t>* parent_of) {
  order->clear();
  order->push_back(root);
  (*seen)[root] = 1;
  (*parent_of)[root] = -1;
  for (size_t h = 0; h < order->size(); ++h) {
    const int32_t u = (*order)[h];
    for (int32_t e = f.offset[u]; e < f.offset[u + 1]; ++e) {
      const int32_t v = f.target[e];
      if ((*seen)[v]) continue;
      (*seen)[v] = 1;
      (*parent_of)[v] = u;
      order->push_back(v);
    }
  }
}

// The tree's member farthest from the members' centroid (lowest index among equals), with its
// normal turned away from the centroid.
int32_t OutwardSeed(const std::vector<Point3>& points, const std::vector<int32_t>& members,
                    std::vector<Point3>* normals) {
  Point3 c{0, 0, 0};
  for (int32_t m : members)
    for (int a = 0; a < 3; ++a) c[a] += points[m][a];
  for (double& x : c) x /= static_cast<double>(members.size());
  int32_t seed = members[0];
  double best = -1;
  for (int32_t m : members) {
    const Point3 d{points[m][0] - c[0], points[m][1] - c[1], points[m][2] - c[2]};
    const double d2 = Dot(d, d);
    if (d2 > best || (d2 == best && m < seed)) best = d2, seed = m;
  }
  const Point3 out{points[seed][0] - c[0], points[seed][1] - c[1], points[seed][2] - c[2]};
  Point3& n = (*normals)[seed];
  if (Dot(n, out) < 0)
    for (double& x : n) x = -x;
  return seed;
}

// Divergence theorem: over a closed surface, the integral of n . (p - c) is 3 x the volume, so
// outward normals give a positive sum over uniform samples; a tree whose sum is negative is
// reversed as a whole (this corrects a seed whose own normal was unreliable, e.g. at a tip).
void VoteOutward(const std::vector<Point3>& points, const std::vector<int32_t>& members, std::vector<Point3>* normals) {
  Point3 c{0, 0, 0};
  for (int32_t m : members)
    for (int a = 0; a < 3; ++a) c[a] += points[m][a];
  for (double& x : c) x /= static_cast<double>(members.size());
  double sum = 0;
  for (int32_t m : members)
    sum += Dot((*normals)[m], Point3{points[m][0] - c[0], points[m][1] - c[1], points[m][2] - c[2]});
  if (sum < 0)
    for (int32_t m : members)
      for (double& x : (*normals)[m]) x = -x;
}

}  // namespace

StatusOr<int32_t> OrientNormals(const std::vector<Point3>& points, const KnnGraph& graph, std::vector<Point3>* normals,
                                const CancelCheck& cancel) {
  const size_t n = points.size();
  SILK_ASSIGN_OR_RETURN(const Forest f, SpanningForest(graph, *normals, cancel));
  std::vector<char> seen(n, 0), reseen(n, 0);
  std::vector<int32_t> members, order, parent_of(n, -1);
  int32_t trees = 0;
  for (size_t start = 0; start < n; ++start) {
    if (seen[start]) continue;
    ++trees;
    TreeOrder(f, static_cast<int32_t>(start), &seen, &members, &parent_of);
    const int32_t seed = OutwardSeed(points, members, normals);
    TreeOrder(f, seed, &reseen, &order, &parent_of);
    for (size_t h = 1; h < order.size(); ++h) {
      const int32_t v = order[h];
      Point3& nv = (*normals)[v];
      if (Dot(nv, (*normals)[parent_of[v]]) < 0)
        for (double& x : nv) x = -x;
    }
    VoteOutward(points, order, normals);
  }
  return trees;
}

}  // namespace silk
