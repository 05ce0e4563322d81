// SPDX-License-Identifier: MIT
// Gap faces between the fans of a bowtie vertex, then splitting what remains (rules in
// vertex_fan_rules.h and docs/grammar.md).
#include "decoder/vertex_fan_rules.h"

#include <algorithm>
#include <cstdlib>
#include <set>

#include "mesh/vertex_fans.h"
#include "tokenizer/cleanup/collinear.h"

namespace silk {
namespace {

uint64_t EdgeKey(int32_t a, int32_t b) {
  if (a > b) std::swap(a, b);
  return (static_cast<uint64_t>(static_cast<uint32_t>(a)) << 32) | static_cast<uint32_t>(b);
}

struct Chain {
  int32_t start = -1, end = -1;  // open fan: faces (v, x, y) chain start -> ... -> end
};

// The open fans at v: in an edge-manifold, oriented mesh a fan is a path or a cycle of faces
// (v, x, y); a path starts at the x that is no face's y and ends at the y that is no face's x.
std::vector<Chain> OpenChains(const std::vector<std::array<int32_t, 3>>& faces, const std::vector<int32_t>& at_v,
                              const std::vector<int32_t>& corner_fan, int32_t v, int32_t fans) {
  std::vector<std::vector<std::array<int32_t, 2>>> spokes(static_cast<size_t>(fans));
  for (int32_t fi : at_v) {
    const auto& f = faces[fi];
    const int32_t k = f[0] == v ? 0 : f[1] == v ? 1 : 2;
    spokes[corner_fan[fi * 3 + k]].push_back({f[(k + 1) % 3], f[(k + 2) % 3]});
  }
  std::vector<Chain> chains;
  for (const auto& s : spokes) {
    Chain c;
    for (const auto& xy : s) {
      bool is_y = false, is_x = false;
      for (const auto& o : s) {
        is_y = is_y || o[1] == xy[0];
        is_x = is_x || o[0] == xy[1];
      }
      if (!is_y) c.start = xy[0];
      if (!is_x) c.end = xy[1];
    }
    if (c.start >= 0 && c.end >= 0) chains.push_back(c);
  }
  return chains;
}

int64_t Dist2(const QVec& a, const QVec& b) {
  const int64_t dx = a.x - b.x, dy = a.y - b.y, dz = a.z - b.z;
  return dx * dx + dy * dy + dz * dz;
}

// Rule "close the gap": join the end e of one open fan to the start s of another with the face
// (v, e, s) when e-s is a new edge between equal or adjacent layers (like a hole chord, spec
// §12.2) and the face has non-zero area. Its edges v-e and s-v each had one face, so the mesh
// stays edge-manifold and oriented, and e and s keep their fan count. Shortest gap first.
int32_t CloseGapsAt(int32_t v, std::vector<std::array<int32_t, 3>>* faces, std::vector<std::vector<int32_t>>* at,
                    std::set<uint64_t>* edges, const std::vector<QVec>& pos, const std::vector<int32_t>& layer_of) {
  const VertexFans vf = ComputeVertexFans(*faces, static_cast<int32_t>(pos.size()));
  std::vector<Chain> chains = OpenChains(*faces, (*at)[v], vf.corner_fan, v, vf.fans_per_vertex[v]);
  int32_t closed = 0;
  while (chains.size() >= 2) {
    int64_t best = -1;
    size_t bi = 0, bj = 0;
    for (size_t i = 0; i < chains.size(); ++i)
      for (size_t j = 0; j < chains.size(); ++j) {
        const int32_t e = chains[i].end, s = chains[j].start;
        if (i == j || e == s || edges->count(EdgeKey(e, s)) || std::abs(layer_of[e] - layer_of[s]) > 1) continue;
        if (pos[e] == pos[s] || pos[v] == pos[e] || pos[v] == pos[s] || Collinear(pos[v], pos[e], pos[s])) continue;
        const int64_t d = Dist2(pos[e], pos[s]);
        if (best < 0 || d < best) best = d, bi = i, bj = j;
      }
    if (best < 0) break;
    const int32_t e = chains[bi].end, s = chains[bj].start;
    const int32_t fi = static_cast<int32_t>(faces->size());
    faces->push_back({v, e, s});
    for (int32_t c : {v, e, s}) (*at)[c].push_back(fi);
    edges->insert(EdgeKey(e, s));
    chains[bi].end = chains[bj].end;
    chains.erase(chains.begin() + static_cast<std::ptrdiff_t>(bj));
    ++closed;
  }
  return closed;
}

}  // namespace

void ResolveVertexFans(std::vector<std::array<int32_t, 3>>* faces, const std::vector<QVec>& positions,
                       const std::vector<int32_t>& layer_of, bool close_gaps, std::vector<int32_t>* copy_of,
                       VertexFanCounts* counts) {
  const int32_t nv = static_cast<int32_t>(positions.size());
  const VertexFans vf = ComputeVertexFans(*faces, nv);
  if (vf.nonmanifold_vertices == 0) return;
  counts->nonmanifold_vertices += static_cast<int32_t>(vf.nonmanifold_vertices);
  if (close_gaps) {
    std::vector<std::vector<int32_t>> at(static_cast<size_t>(nv));
    std::set<uint64_t> edges;
    for (size_t fi = 0; fi < faces->size(); ++fi)
      for (int k = 0; k < 3; ++k) {
        at[(*faces)[fi][k]].push_back(static_cast<int32_t>(fi));
        edges.insert(EdgeKey((*faces)[fi][k], (*faces)[fi][(k + 1) % 3]));
      }
    for (int32_t v = 0; v < nv; ++v)
      if (vf.fans_per_vertex[v] >= 2) counts->gaps_closed += CloseGapsAt(v, faces, &at, &edges, positions, layer_of);
  }
  // Rule "split": every vertex still with several fans gets one copy per extra fan.
  const size_t before = copy_of->size();
  counts->vertices_split += SplitNonManifoldFans(faces, nv, copy_of);
  counts->vertex_copies += static_cast<int32_t>(copy_of->size() - before);
}

}  // namespace silk
