// DecodeTokens: ids -> LayeredStream (token_reader) -> adjacency per layer (self/between
// decoders) -> faces per component (face_recovery) -> one mesh in reading order.
#include <string>

#include "tokenizer/face_recovery.h"
#include "tokenizer/layer_adjacency.h"
#include "tokenizer/token_reader.h"
#include "tokenizer/tokenizer.h"

namespace silk {

StatusOr<DecodedMesh> DecodeTokens(const std::vector<int32_t>& ids, const DecodeOptions& options) {
  if (options.official_faces) {
    return Unsupported("the official decoder's face rule (spec §10.3) is not implemented");
  }
  SILK_ASSIGN_OR_RETURN(LayeredStream stream, ReadTokens(ids));
  DecodedMesh mesh;
  for (size_t ci = 0; ci < stream.components.size(); ++ci) {
    const StreamComponent& comp = stream.components[ci];
    ComponentLayers layers;
    int32_t prev_size = 0;
    for (size_t l = 0; l < comp.layers.size(); ++l) {
      std::vector<QVec> pos;
      pos.reserve(comp.layers[l].vertices.size());
      for (const auto& v : comp.layers[l].vertices) pos.push_back(v.pos);
      if (l > 0) {
        auto adj = DecodeLayerAdjacency(comp.layers[l], prev_size);
        if (!adj.ok()) {
          return adj.status().WithContext("component " + std::to_string(ci) + ", layer " + std::to_string(l) + ": ");
        }
        layers.adjacency.push_back(std::move(adj).value());
      }
      prev_size = static_cast<int32_t>(pos.size());
      layers.layer_positions.push_back(std::move(pos));
    }
    auto faces = RecoverComponentFaces(layers);
    if (!faces.ok()) return faces.status().WithContext("component " + std::to_string(ci) + ": ");
    const int32_t base = static_cast<int32_t>(mesh.positions.size());
    for (const auto& layer : layers.layer_positions) {
      for (const QVec& q : layer) {
        mesh.positions.push_back(q);
        mesh.vertex_component.push_back(static_cast<int32_t>(ci));
      }
    }
    for (const auto& f : *faces) {
      mesh.faces.push_back({f[0] + base, f[1] + base, f[2] + base});
      mesh.face_component.push_back(static_cast<int32_t>(ci));
    }
  }
  mesh.components = static_cast<int32_t>(stream.components.size());
  return mesh;
}

}  // namespace silk
