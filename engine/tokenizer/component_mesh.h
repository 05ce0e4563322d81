// SPDX-License-Identifier: MIT
// TokenizerComponentMesh: one component assembled from its ids (layers -> adjacency -> faces), the
// one assembly step shared by DecodeTokens (silktok decode, the C API) and the decoder's BuildMesh
// (generation), so positions, vertex order and face recovery cannot drift apart between the two.
// AppendComponentMesh puts components together into a TokenizerDecodedMesh (docs/mesh_types.md).
#pragma once
#include <array>
#include <cstdint>
#include <vector>

#include "core/status.h"
#include "tokenizer/layering/layered_stream.h"
#include "tokenizer/tokenizer.h"

namespace silk {

struct TokenizerComponentMesh {
  std::vector<QVec> positions;  // reading order: root, layer 1, layer 2, ...
  std::vector<int32_t> layer_of, index_in_layer;
  std::vector<std::array<int32_t, 3>> faces;  // local indices, oriented (face_recovery.h)
  int32_t dropped_degenerate = 0;             // zero-area recovered faces dropped
};

// Assembles the first `closed_layers` layers of `comp` (all when < 0). Errors name the layer.
StatusOr<TokenizerComponentMesh> AssembleComponentMesh(const StreamComponent& comp, int32_t closed_layers = -1);

// Appends a component's vertices and faces to `mesh` as component `ci`.
void AppendComponentMesh(const TokenizerComponentMesh& cm, int32_t ci, TokenizerDecodedMesh* mesh);

}  // namespace silk
