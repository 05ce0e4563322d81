// SPDX-License-Identifier: MIT
// Face adjacency and orientation repair (token_format.md §3.7-§3.8).
#include "tokenizer/manifold/orientation_repair.h"

#include <algorithm>
#include <string>
#include <utility>

#include "tokenizer/refusal.h"

namespace silk {
namespace {

// +1 if face t contains the directed edge u->w, -1 if it contains w->u, 0 otherwise.
int Direction(const Tri& t, VertexId u, VertexId w) {
  for (int k = 0; k < 3; ++k) {
    if (t[k] == u && t[(k + 1) % 3] == w) return 1;
    if (t[k] == w && t[(k + 1) % 3] == u) return -1;
  }
  return 0;
}

void Flip(Tri& t) { std::swap(t[1], t[2]); }

}  // namespace

StatusOr<FaceAdjacency> BuildFaceAdjacency(const TokenizerProcessedMesh& mesh) {
  struct E {
    int32_t lo, hi, face, slot;
  };
  const int32_t nf = mesh.face_count();
  std::vector<E> edges;
  edges.reserve(static_cast<size_t>(nf) * 3);
  for (int32_t f = 0; f < nf; ++f) {
    const Tri& t = mesh.faces[static_cast<size_t>(f)];
    for (int k = 0; k < 3; ++k) {
      int32_t a = t[k].get(), b = t[(k + 1) % 3].get();
      edges.push_back({std::min(a, b), std::max(a, b), f, k});
    }
  }
  std::sort(edges.begin(), edges.end(), [](const E& x, const E& y) {
    if (x.lo != y.lo) return x.lo < y.lo;
    if (x.hi != y.hi) return x.hi < y.hi;
    return x.face < y.face;
  });
  FaceAdjacency adj;
  adj.nbr.assign(static_cast<size_t>(nf), {FaceId(), FaceId(), FaceId()});
  for (size_t i = 0; i < edges.size();) {
    size_t j = i;
    while (j < edges.size() && edges[j].lo == edges[i].lo && edges[j].hi == edges[i].hi) ++j;
    if (j - i >= 3)
      return Refuse(Refusal::kMeetNonManifold, "edge (" + std::to_string(edges[i].lo) + ", " +
                                                   std::to_string(edges[i].hi) + ") has " + std::to_string(j - i) +
                                                   " faces");
    if (j - i == 2) {
      adj.nbr[static_cast<size_t>(edges[i].face)][static_cast<size_t>(edges[i].slot)] = FaceId(edges[i + 1].face);
      adj.nbr[static_cast<size_t>(edges[i + 1].face)][static_cast<size_t>(edges[i + 1].slot)] = FaceId(edges[i].face);
    }
    i = j;
  }
  return adj;
}

Status RepairOrientation(TokenizerProcessedMesh& mesh, FaceAdjacency& adj, int32_t* flipped_faces) {
  const int32_t nf = mesh.face_count();
  std::vector<int32_t> set_of(static_cast<size_t>(nf), -1);
  std::vector<char> flipped(static_cast<size_t>(nf), 0);
  std::vector<int32_t> queue;
  int32_t n_sets = 0, n_flipped = 0;

  // Neighbour slots are tied to corner order; a flip swaps corners 1,2, so edge slots
  // (0:c0c1, 1:c1c2, 2:c2c0) become (0:c0c2 = old 2, 1:c2c1 = old 1, 2:c1c0 = old 0).
  auto flip_face = [&](int32_t f) {
    Flip(mesh.faces[static_cast<size_t>(f)]);
    std::swap(adj.nbr[static_cast<size_t>(f)][0], adj.nbr[static_cast<size_t>(f)][2]);
    flipped[static_cast<size_t>(f)] ^= 1;
  };

  for (int32_t seed = 0; seed < nf; ++seed) {
    if (set_of[static_cast<size_t>(seed)] >= 0) continue;
    const int32_t id = n_sets++;
    // Seed majority vote (token_format.md §3.7 step 2, §14.C.3).
    int consistent = 0;
    for (int k = 0; k < 3; ++k) {
      const FaceId g = adj.nbr[static_cast<size_t>(seed)][static_cast<size_t>(k)];
      if (!g.valid()) {
        ++consistent;
        continue;
      }
      const Tri& t = mesh.faces[static_cast<size_t>(seed)];
      if (Direction(mesh.face(g), t[k], t[(k + 1) % 3]) == -1) ++consistent;
    }
    if (consistent < 2) flip_face(seed);
    set_of[static_cast<size_t>(seed)] = id;
    queue.assign(1, seed);
    for (size_t qi = 0; qi < queue.size(); ++qi) {
      const int32_t f = queue[qi];
      for (int k = 0; k < 3; ++k) {
        const FaceId g = adj.nbr[static_cast<size_t>(f)][static_cast<size_t>(k)];
        if (!g.valid()) continue;
        const Tri& t = mesh.faces[static_cast<size_t>(f)];
        const VertexId u = t[k], w = t[(k + 1) % 3];
        const int dir = Direction(mesh.face(g), u, w);
        if (set_of[static_cast<size_t>(g.get())] < 0) {
          if (dir == 1) flip_face(g.get());
          set_of[static_cast<size_t>(g.get())] = id;
          queue.push_back(g.get());
        } else if (dir == 1) {
          return Refuse(Refusal::kMobius, "faces " + std::to_string(f) + " and " + std::to_string(g.get()) +
                                              " cannot be oriented consistently (non-orientable surface)");
        }
      }
    }
  }
  for (char c : flipped) n_flipped += c;

  // §3.8: a vertex used by faces of two edge-connected sets.
  std::vector<int32_t> vertex_set(static_cast<size_t>(mesh.vertex_count()), -1);
  for (int32_t f = 0; f < nf; ++f) {
    for (VertexId v : mesh.faces[static_cast<size_t>(f)]) {
      int32_t& s = vertex_set[static_cast<size_t>(v.get())];
      if (s < 0)
        s = set_of[static_cast<size_t>(f)];
      else if (s != set_of[static_cast<size_t>(f)])
        return Refuse(Refusal::kVertexSharedByComponents,
                      "vertex " + std::to_string(v.get()) + " is shared by two edge-connected components");
    }
  }
  if (flipped_faces) *flipped_faces = n_flipped;
  return Status::Ok();
}

}  // namespace silk
