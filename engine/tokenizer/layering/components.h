// SPDX-License-Identifier: MIT
// Face order, connected components, small-component removal and the face limit
// (token_format.md §4.1-§4.3): decides which components are emitted and in which order.
#pragma once
#include <vector>

#include "core/status.h"
#include "tokenizer/manifold/orientation_repair.h"
#include "tokenizer/processed_mesh.h"

namespace silk {

struct Component {
  std::vector<FaceId> faces;  // in sorted face order (§4.1)
};

struct ComponentSplit {
  std::vector<Component> kept;  // emission order
  int32_t found = 0;
  int32_t dropped_small = 0;  // components with < 3 faces
};

// Refuses no-faces (nothing survived cleanup), face-limit (> 12000 kept faces) and
// all-components-dropped.
StatusOr<ComponentSplit> FindComponents(const TokenizerProcessedMesh& mesh, const FaceAdjacency& adjacency);

// Sort key of a face: (Σy, Σz, Σx) of its corners (§4.1).
std::array<int32_t, 3> FaceSortKey(const TokenizerProcessedMesh& mesh, FaceId f);

}  // namespace silk
