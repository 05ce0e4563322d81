// SPDX-License-Identifier: MIT
// Root choice and BFS layering with the reference's first-run rule (token_format.md §4.4, §5.2-§5.3).
// Also records each vertex's (layer, position) so the matrix codecs can index layers.
#pragma once
#include <vector>

#include "core/status.h"
#include "tokenizer/layering/components.h"
#include "tokenizer/layering/rotation_lists.h"

namespace silk {

struct ComponentVertexLayers {
  std::vector<std::vector<VertexId>> layers;  // layers[0] = {root}
};

struct Layering {
  std::vector<ComponentVertexLayers> components;  // one per kept component, emission order
  std::vector<int32_t> layer_of;                  // by VertexId; -1 = not emitted
  std::vector<int32_t> index_in_layer;            // by VertexId; -1 = not emitted
};

// Root of a component: the corner with the smallest (y, z, x) of its first sorted face.
VertexId ComponentRoot(const TokenizerProcessedMesh& mesh, const Component& c);

// Refuses layer-count-limit (a component needing layer index 200) and layer-size-limit
// (any layer > 200 vertices, checked after all components are layered).
StatusOr<Layering> BuildLayers(const TokenizerProcessedMesh& mesh, const std::vector<Component>& kept,
                               const RotationLists& rotation);

}  // namespace silk
