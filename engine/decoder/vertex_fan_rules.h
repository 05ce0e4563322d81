// SPDX-License-Identifier: MIT
// The vertex-manifold rule of decoded meshes (docs/grammar.md "Vertex fans"). Faces are only
// known once a component's layers are closed (face recovery, token_format.md §10.6), so whether a vertex
// ends with one fan cannot be decided by the legal mask; it is resolved when the component's
// mesh is assembled: close the gap between two fans with one face when the repair policy
// allows, otherwise (or when no such face is legal) split the vertex once per extra fan.
#pragma once
#include <array>
#include <cstdint>
#include <vector>

#include "tokenizer/cleanup/quantize.h"

namespace silk {

struct VertexFanCounts {
  int32_t nonmanifold_vertices = 0;  // vertices with two or more fans before the rule
  int32_t gaps_closed = 0;           // faces added between two fans (repair policy only)
  int32_t vertices_split = 0;        // vertices still with several fans, split
  int32_t vertex_copies = 0;         // vertices appended by the splits
};

// One component (local vertex ids). `close_gaps`: try the gap faces first. Appends a copy's
// source to *copy_of for every vertex added (callers duplicate position and layer).
void ResolveVertexFans(std::vector<std::array<int32_t, 3>>* faces, const std::vector<QVec>& positions,
                       const std::vector<int32_t>& layer_of, bool close_gaps, std::vector<int32_t>* copy_of,
                       VertexFanCounts* counts);

}  // namespace silk
