// SPDX-License-Identifier: MIT
// Rotation lists R(v) (token_format.md §5.1), built from each vertex's (a_f, b_f) corner pairs taken
// in the component's sorted face order.
#include "tokenizer/layering/rotation_lists.h"

#include <string>

#include "tokenizer/refusal.h"

namespace silk {

StatusOr<RotationLists> BuildRotationLists(const TokenizerProcessedMesh& mesh, const std::vector<Component>& kept) {
  const size_t nv = static_cast<size_t>(mesh.vertex_count());
  // Per vertex: its (a_f, b_f) pairs in sorted face order, CSR.
  std::vector<int32_t> pair_begin(nv + 1, 0);
  for (const Component& c : kept)
    for (FaceId f : c.faces)
      for (VertexId v : mesh.face(f)) ++pair_begin[static_cast<size_t>(v.get()) + 1];
  for (size_t i = 0; i < nv; ++i) pair_begin[i + 1] += pair_begin[i];
  std::vector<std::pair<VertexId, VertexId>> pairs(static_cast<size_t>(pair_begin[nv]));
  std::vector<int32_t> fill(pair_begin.begin(), pair_begin.end() - 1);
  for (const Component& c : kept) {
    for (FaceId f : c.faces) {
      const Tri& t = mesh.face(f);
      for (int k = 0; k < 3; ++k)
        pairs[static_cast<size_t>(fill[static_cast<size_t>(t[k].get())]++)] = {t[(k + 1) % 3], t[(k + 2) % 3]};
    }
  }

  RotationLists out;
  out.begin.assign(nv + 1, 0);
  out.items.reserve(pairs.size() + nv);
  for (size_t v = 0; v < nv; ++v) {
    out.begin[v] = static_cast<int32_t>(out.items.size());
    const auto* p = pairs.data() + pair_begin[v];
    const int32_t n = pair_begin[v + 1] - pair_begin[v];
    if (n == 0) continue;
    auto next_of = [&](VertexId a, VertexId* b) {
      for (int32_t i = 0; i < n; ++i)
        if (p[i].first == a) {
          *b = p[i].second;
          return true;
        }
      return false;
    };
    // Boundary: an a_f that is no b_g (directed edge v->a_f has no opposite).
    int32_t n_starts = 0;
    VertexId start = p[0].first;
    for (int32_t i = 0; i < n; ++i) {
      bool is_b = false;
      for (int32_t j = 0; j < n && !is_b; ++j) is_b = p[j].second == p[i].first;
      if (!is_b) {
        if (n_starts == 0) start = p[i].first;
        ++n_starts;
      }
    }
    if (n_starts > 1)
      return Refuse(Refusal::kBoundaryVertex,
                    "vertex " + std::to_string(v) + " has " + std::to_string(n_starts) + " outgoing boundary edges");
    VertexId cur = start;
    out.items.push_back(cur);
    if (n_starts == 1) {
      VertexId nx;
      for (int32_t guard = 0; guard < n && next_of(cur, &nx); ++guard) {
        out.items.push_back(nx);
        cur = nx;
      }
    } else {
      VertexId nx;
      for (int32_t guard = 0; guard < n - 1 && next_of(cur, &nx) && nx != start; ++guard) {
        out.items.push_back(nx);
        cur = nx;
      }
    }
  }
  out.begin[nv] = static_cast<int32_t>(out.items.size());
  return out;
}

}  // namespace silk
