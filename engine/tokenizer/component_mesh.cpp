// SPDX-License-Identifier: MIT
// Layers -> decoded adjacency (self/between decoders) -> oriented faces (face recovery); zero-area
// triangles are dropped (the grammar's "no degenerate face" guarantee; the official streams
// give none, component_graph already leaves collinear 3-cycles out).
#include "tokenizer/component_mesh.h"

#include <algorithm>
#include <string>

#include "tokenizer/cleanup/collinear.h"
#include "tokenizer/face_recovery/face_recovery.h"
#include "tokenizer/adjacency/layer_adjacency.h"

namespace silk {

StatusOr<TokenizerComponentMesh> AssembleComponentMesh(const StreamComponent& comp, int32_t closed_layers) {
  TokenizerComponentMesh cm;
  ComponentLayers layers;
  int32_t prev = 0;
  const int32_t count = closed_layers < 0 ? static_cast<int32_t>(comp.layers.size()) : closed_layers;
  for (int32_t l = 0; l < count; ++l) {
    std::vector<QVec> pos;
    pos.reserve(comp.layers[l].vertices.size());
    for (size_t i = 0; i < comp.layers[l].vertices.size(); ++i) {
      pos.push_back(comp.layers[l].vertices[i].pos);
      cm.positions.push_back(comp.layers[l].vertices[i].pos);
      cm.layer_of.push_back(l);
      cm.index_in_layer.push_back(static_cast<int32_t>(i));
    }
    if (l > 0) {
      auto adj = DecodeLayerAdjacency(comp.layers[l], prev);
      if (!adj.ok()) return adj.status().WithContext("layer " + std::to_string(l) + ": ");
      layers.adjacency.push_back(std::move(adj).value());
    }
    prev = static_cast<int32_t>(pos.size());
    layers.layer_positions.push_back(std::move(pos));
  }
  if (layers.layer_positions.size() < 2) return cm;
  using Faces = std::vector<std::array<int32_t, 3>>;
  SILK_ASSIGN_OR_RETURN(Faces faces, RecoverComponentFaces(layers));
  cm.faces.reserve(faces.size());
  for (const auto& f : faces) {
    if (Collinear(cm.positions[f[0]], cm.positions[f[1]], cm.positions[f[2]])) {
      ++cm.dropped_degenerate;
      continue;
    }
    cm.faces.push_back(f);
  }
  return cm;
}

void AppendComponentMesh(const TokenizerComponentMesh& cm, int32_t ci, TokenizerDecodedMesh* mesh) {
  const int32_t base = static_cast<int32_t>(mesh->positions.size());
  for (const QVec& q : cm.positions) {
    mesh->positions.push_back(q);
    mesh->vertex_component.push_back(ci);
  }
  for (const auto& f : cm.faces) {
    mesh->faces.push_back({f[0] + base, f[1] + base, f[2] + base});
    mesh->face_component.push_back(ci);
  }
  mesh->components = std::max(mesh->components, ci + 1);
}

}  // namespace silk
