// SPDX-License-Identifier: MIT
// Combines the self-layer and between-layer decoders into one LayerAdjacency.
#include "tokenizer/adjacency/layer_adjacency.h"

#include "tokenizer/adjacency/between_layer_decoder.h"
#include "tokenizer/adjacency/self_layer_decoder.h"

namespace silk {

StatusOr<LayerAdjacency> DecodeLayerAdjacency(const StreamLayer& layer, int32_t prev_size) {
  LayerAdjacency adj;
  SILK_ASSIGN_OR_RETURN(adj.self_edges, DecodeSelfLayer(layer));
  SILK_ASSIGN_OR_RETURN(adj.between_edges, DecodeBetweenLayer(layer, prev_size));
  return adj;
}

}  // namespace silk
