// SPDX-License-Identifier: MIT
// Face order and connected components (token_format.md §4.1-§4.3).
#include "tokenizer/layering/components.h"

#include <algorithm>
#include <numeric>
#include <string>

#include "tokenizer/refusal.h"
#include "tokenizer/vocabulary_layout.h"

namespace silk {

std::array<int32_t, 3> FaceSortKey(const TokenizerProcessedMesh& mesh, FaceId f) {
  std::array<int32_t, 3> k{0, 0, 0};
  for (VertexId v : mesh.face(f)) {
    const QVec& q = mesh.pos(v);
    k[0] += q.y;
    k[1] += q.z;
    k[2] += q.x;
  }
  return k;
}

StatusOr<ComponentSplit> FindComponents(const TokenizerProcessedMesh& mesh, const FaceAdjacency& adj) {
  const int32_t nf = mesh.face_count();
  if (nf == 0) return Refuse(Refusal::kNoFaces, "no face survived quantization and cleanup");
  std::vector<std::array<int32_t, 3>> keys(static_cast<size_t>(nf));
  for (int32_t f = 0; f < nf; ++f) keys[static_cast<size_t>(f)] = FaceSortKey(mesh, FaceId(f));
  std::vector<int32_t> order(static_cast<size_t>(nf));
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(),
                   [&](int32_t a, int32_t b) { return keys[static_cast<size_t>(a)] < keys[static_cast<size_t>(b)]; });
  std::vector<int32_t> rank(static_cast<size_t>(nf));
  for (int32_t r = 0; r < nf; ++r) rank[static_cast<size_t>(order[static_cast<size_t>(r)])] = r;

  std::vector<int32_t> label(static_cast<size_t>(nf), -1);
  std::vector<std::vector<int32_t>> members;
  std::vector<int32_t> stack;
  for (int32_t r = 0; r < nf; ++r) {
    const int32_t start = order[static_cast<size_t>(r)];
    if (label[static_cast<size_t>(start)] >= 0) continue;
    const int32_t id = static_cast<int32_t>(members.size());
    members.emplace_back();
    label[static_cast<size_t>(start)] = id;
    stack.assign(1, start);
    while (!stack.empty()) {
      const int32_t f = stack.back();
      stack.pop_back();
      members[static_cast<size_t>(id)].push_back(f);
      for (FaceId g : adj.nbr[static_cast<size_t>(f)]) {
        if (g.valid() && label[static_cast<size_t>(g.get())] < 0) {
          label[static_cast<size_t>(g.get())] = id;
          stack.push_back(g.get());
        }
      }
    }
  }

  ComponentSplit out;
  out.found = static_cast<int32_t>(members.size());
  int64_t total = 0;
  for (auto& m : members) {
    if (m.size() < 3) {
      ++out.dropped_small;
      continue;
    }
    std::sort(m.begin(), m.end(),
              [&](int32_t a, int32_t b) { return rank[static_cast<size_t>(a)] < rank[static_cast<size_t>(b)]; });
    Component c;
    c.faces.reserve(m.size());
    for (int32_t f : m) c.faces.push_back(FaceId(f));
    total += static_cast<int64_t>(m.size());
    out.kept.push_back(std::move(c));
  }
  if (total > vocab::k_max_faces)
    return Refuse(Refusal::kTooManyFaces,
                  std::to_string(total) + " faces in kept components > " + std::to_string(vocab::k_max_faces));
  return out;
}

}  // namespace silk
