// SPDX-License-Identifier: MIT
// Face adjacency across edges and orientation repair (token_format.md §3.7-§3.8): after non-manifold
// splitting every edge has at most two faces; each edge-connected set is oriented like its seed.
#pragma once
#include <array>
#include <vector>

#include "core/status.h"
#include "tokenizer/processed_mesh.h"

namespace silk {

// nbr[f][k]: the face across face f's edge k = (corner k, corner k+1), or -1 on a boundary.
// Edge slots follow the corners, so they stay valid when a face is flipped by swapping
// corners 1 and 2 only if re-derived; use FaceAcross() rather than caching slots.
struct FaceAdjacency {
  std::vector<std::array<FaceId, 3>> nbr;
};

// Refuses (non-manifold-edge) when an undirected edge has three or more faces.
StatusOr<FaceAdjacency> BuildFaceAdjacency(const TokenizerProcessedMesh& mesh);

// Orients every edge-connected face set consistently with its lowest-index face (flipped
// first if fewer than 2 of its edges agree with their neighbours). Refuses (mobius) when a
// set is not orientable and (vertex-shared-by-components) when a vertex touches two sets.
Status RepairOrientation(TokenizerProcessedMesh& mesh, FaceAdjacency& adjacency, int32_t* flipped_faces);

}  // namespace silk
