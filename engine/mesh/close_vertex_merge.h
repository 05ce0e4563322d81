// SPDX-License-Identifier: MIT
// The official pre-processing's mesh cleaning (official_network.md §4 step 3): unreferenced
// vertices removed, vertices closer than a distance merged, then duplicate and zero-area faces
// dropped, so that surface samples come from the same surface the network was trained on.
#pragma once
#include <cstdint>

#include "io/io_mesh.h"

namespace silk {

struct VertexMergeReport {
  int64_t vertices_before = 0, vertices_after = 0;
  int64_t faces_before = 0, faces_after = 0;
};

// Diagonal of the bounding box of the vertices that faces reference (0 when there are none).
double ReferencedBoundingBoxDiagonal(const IoMesh& mesh);

// Merging is leader clustering in vertex order on a uniform grid of cell `distance`: a vertex
// joins the nearest earlier leader strictly closer than `distance` (looked up in the 27
// surrounding cells), otherwise it becomes a leader; merged vertices take their leader's
// position. Unlike transitive (union-find) merging, no vertex moves by `distance` or more, and
// the result depends only on the vertex order. distance <= 0 merges nothing. Afterwards faces
// with a repeated vertex or zero area, and repeats of a face (same three vertices in any
// order; the first is kept), are dropped, and vertices no face references are removed.
// Triangle indices must be in range (validated input).
IoMesh MergeCloseVertices(const IoMesh& mesh, double distance, VertexMergeReport* report = nullptr);

}  // namespace silk
