// SPDX-License-Identifier: MIT
// Rotation lists R(v) (token_format.md §5.1): each vertex's neighbours in the rotational order its
// faces' windings give. They drive the layering and both adjacency matrices.
#pragma once
#include <vector>

#include "core/status.h"
#include "tokenizer/layering/components.h"
#include "tokenizer/processed_mesh.h"

namespace silk {

// CSR storage: R(v) = items[begin[v] .. begin[v+1]).
struct RotationLists {
  std::vector<int32_t> begin;
  std::vector<VertexId> items;
  const VertexId* first(VertexId v) const { return items.data() + begin[static_cast<size_t>(v.get())]; }
  int32_t size(VertexId v) const {
    return begin[static_cast<size_t>(v.get()) + 1] - begin[static_cast<size_t>(v.get())];
  }
};

// Builds R(v) for every vertex of the kept components (others get empty lists).
// Refuses bad-boundary-vertex when a vertex has more than one outgoing boundary edge.
StatusOr<RotationLists> BuildRotationLists(const TokenizerProcessedMesh& mesh, const std::vector<Component>& kept);

}  // namespace silk
