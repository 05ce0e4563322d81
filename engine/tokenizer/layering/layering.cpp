// SPDX-License-Identifier: MIT
// BFS layering with the first-run rule (token_format.md §5.2-§5.3, quirk §14.C.1: do not "fix" it).
#include "tokenizer/layering/layering.h"

#include <string>

#include "tokenizer/refusal.h"
#include "tokenizer/vocabulary_layout.h"

namespace silk {

VertexId ComponentRoot(const TokenizerProcessedMesh& mesh, const Component& c) {
  const Tri& t = mesh.face(c.faces.front());
  VertexId best = t[0];
  for (int k = 1; k < 3; ++k)
    if (LessYZX(mesh.pos(t[k]), mesh.pos(best))) best = t[k];
  return best;
}

StatusOr<Layering> BuildLayers(const TokenizerProcessedMesh& mesh, const std::vector<Component>& kept,
                               const RotationLists& rotation) {
  const size_t nv = static_cast<size_t>(mesh.vertex_count());
  Layering out;
  out.layer_of.assign(nv, -1);
  out.index_in_layer.assign(nv, -1);
  std::vector<char> visited(nv, 0);
  std::vector<int32_t> collected_stamp(nv, -1);  // layer stamp: already in the layer being built
  int32_t stamp = 0;
  int32_t max_layer = 0;

  for (const Component& comp : kept) {
    ComponentVertexLayers cl;
    const VertexId root = ComponentRoot(mesh, comp);
    cl.layers.push_back({root});
    visited[static_cast<size_t>(root.get())] = 1;
    for (int32_t L = 1;; ++L) {
      if (L > vocab::k_layer_count_limit)
        return Refuse(Refusal::kLayerCountLimit,
                      "a component needs more than " + std::to_string(vocab::k_layer_count_limit) + " layers");
      std::vector<VertexId> layer;
      ++stamp;
      for (VertexId u : cl.layers[static_cast<size_t>(L - 1)]) {
        // §5.2: the first run of unvisited neighbours, cyclically after the first visited one.
        const VertexId* R = rotation.first(u);
        const int32_t n = rotation.size(u);
        int32_t i0 = -1;
        bool any_unvisited = false;
        for (int32_t k = 0; k < n; ++k) {
          if (visited[static_cast<size_t>(R[k].get())]) {
            if (i0 < 0) i0 = k;
          } else {
            any_unvisited = true;
          }
        }
        if (!any_unvisited) continue;
        auto take = [&](VertexId x) {
          if (collected_stamp[static_cast<size_t>(x.get())] != stamp) {
            collected_stamp[static_cast<size_t>(x.get())] = stamp;
            layer.push_back(x);
          }
        };
        if (i0 < 0) {  // every neighbour unvisited (only the root)
          for (int32_t k = 0; k < n; ++k) take(R[k]);
          continue;
        }
        bool started = false;
        for (int32_t k = 1; k < n; ++k) {
          const VertexId x = R[(i0 + k) % n];
          if (visited[static_cast<size_t>(x.get())]) {
            if (started) break;
            continue;
          }
          started = true;
          take(x);
        }
      }
      if (layer.empty()) break;
      for (VertexId x : layer) visited[static_cast<size_t>(x.get())] = 1;
      if (static_cast<int32_t>(layer.size()) > max_layer) max_layer = static_cast<int32_t>(layer.size());
      cl.layers.push_back(std::move(layer));
    }
    for (size_t L = 0; L < cl.layers.size(); ++L)
      for (size_t i = 0; i < cl.layers[L].size(); ++i) {
        out.layer_of[static_cast<size_t>(cl.layers[L][i].get())] = static_cast<int32_t>(L);
        out.index_in_layer[static_cast<size_t>(cl.layers[L][i].get())] = static_cast<int32_t>(i);
      }
    out.components.push_back(std::move(cl));
  }
  if (max_layer > vocab::k_layer_vertex_limit)
    return Refuse(Refusal::kLayerSizeLimit, "a layer has " + std::to_string(max_layer) + " vertices > " +
                                                std::to_string(vocab::k_layer_vertex_limit));
  return out;
}

}  // namespace silk
