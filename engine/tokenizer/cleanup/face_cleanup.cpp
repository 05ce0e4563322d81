// SPDX-License-Identifier: MIT
// Quantization, vertex merging and face cleanup (token_format.md §2.2-§2.4). Sort-based merging and
// duplicate detection: O(n log n), no table sized by the grid.
#include "tokenizer/cleanup/face_cleanup.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "tokenizer/cleanup/collinear.h"

namespace silk {
namespace {

int64_t PackGrid(const QVec& q) { return (static_cast<int64_t>(q.x) << 16) | (static_cast<int64_t>(q.y) << 8) | q.z; }

}  // namespace

StatusOr<TokenizerProcessedMesh> QuantizeAndClean(const IoMesh& in, CleanupStats* stats) {
  CleanupStats local;
  TokenizerProcessedMesh out;
  const size_t nv = in.positions.size();
  out.positions.resize(nv);
  out.input_vertex_count = static_cast<int32_t>(nv);
  for (size_t i = 0; i < nv; ++i) {
    const auto& p = in.positions[i];
    if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2]))
      return InvalidArgument("vertex " + std::to_string(i) + " has a non-finite coordinate");
    out.positions[i] = QVec{QuantizeCoord(p[0]), QuantizeCoord(p[1]), QuantizeCoord(p[2])};
  }

  // §2.3: representative = smallest earlier index with the same grid position.
  std::vector<std::pair<int64_t, int32_t>> keyed(nv);
  for (size_t i = 0; i < nv; ++i) keyed[i] = {PackGrid(out.positions[i]), static_cast<int32_t>(i)};
  std::sort(keyed.begin(), keyed.end());
  std::vector<int32_t> rep(nv);
  for (size_t k = 0; k < nv;) {
    size_t e = k;
    while (e < nv && keyed[e].first == keyed[k].first) ++e;
    for (size_t t = k; t < e; ++t) rep[static_cast<size_t>(keyed[t].second)] = keyed[k].second;
    local.merged_vertices += static_cast<int32_t>(e - k - 1);
    k = e;
  }

  // §2.4 steps 1-3.
  std::vector<Tri> kept;
  kept.reserve(in.triangles.size());
  for (size_t f = 0; f < in.triangles.size(); ++f) {
    Tri t;
    for (int c = 0; c < 3; ++c) {
      const int32_t idx = in.triangles[f][c];
      if (idx < 0 || static_cast<size_t>(idx) >= nv)
        return InvalidArgument("face " + std::to_string(f) + " references vertex " + std::to_string(idx) +
                               " (mesh has " + std::to_string(nv) + " vertices)");
      t[c] = VertexId(rep[static_cast<size_t>(idx)]);
    }
    if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2] || Collinear(out.pos(t[0]), out.pos(t[1]), out.pos(t[2]))) {
      ++local.degenerate_faces;
      continue;
    }
    kept.push_back(t);
  }

  // §2.4 step 4: first occurrence of each corner set wins.
  struct Key {
    int32_t a, b, c;
    int32_t face;
  };
  std::vector<Key> keys(kept.size());
  for (size_t f = 0; f < kept.size(); ++f) {
    int32_t s[3] = {kept[f][0].get(), kept[f][1].get(), kept[f][2].get()};
    std::sort(s, s + 3);
    keys[f] = {s[0], s[1], s[2], static_cast<int32_t>(f)};
  }
  std::sort(keys.begin(), keys.end(), [](const Key& x, const Key& y) {
    if (x.a != y.a) return x.a < y.a;
    if (x.b != y.b) return x.b < y.b;
    if (x.c != y.c) return x.c < y.c;
    return x.face < y.face;
  });
  std::vector<char> drop(kept.size(), 0);
  for (size_t k = 1; k < keys.size(); ++k) {
    if (keys[k].a == keys[k - 1].a && keys[k].b == keys[k - 1].b && keys[k].c == keys[k - 1].c)
      drop[static_cast<size_t>(keys[k].face)] = 1;
  }
  out.faces.reserve(kept.size());
  for (size_t f = 0; f < kept.size(); ++f) {
    if (drop[f]) {
      ++local.duplicate_faces;
      continue;
    }
    out.faces.push_back(kept[f]);
  }
  if (stats) *stats = local;
  return out;
}

}  // namespace silk
