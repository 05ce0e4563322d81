// SPDX-License-Identifier: MIT
// TokenizerProcessedMesh: the mesh between the encoder's stages (token_format.md §2.3-§4): quantized
// positions indexed by processed vertex id (input vertices + non-manifold copies), faces indexed by
// processed face id, each with its current winding. Private to the tokenizer (docs/mesh_types.md;
// tests/tools/check_layers.py keeps other layers from including this header).
#pragma once
#include <array>
#include <vector>

#include "core/strong_id.h"
#include "tokenizer/cleanup/quantize.h"

namespace silk {

using Tri = std::array<VertexId, 3>;

struct TokenizerProcessedMesh {
  std::vector<QVec> positions;  // by VertexId; duplicates/unreferenced entries stay (token_format.md §2.3)
  std::vector<Tri> faces;       // by FaceId (token_format.md §2.4); only corner ids change later
  int32_t input_vertex_count = 0;

  const QVec& pos(VertexId v) const { return positions[static_cast<size_t>(v.get())]; }
  const Tri& face(FaceId f) const { return faces[static_cast<size_t>(f.get())]; }
  Tri& face(FaceId f) { return faces[static_cast<size_t>(f.get())]; }
  int32_t vertex_count() const { return static_cast<int32_t>(positions.size()); }
  int32_t face_count() const { return static_cast<int32_t>(faces.size()); }
};

}  // namespace silk
