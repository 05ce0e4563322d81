// SPDX-License-Identifier: MIT
// The face cap (max_faces) on a built mesh: faces arrive a layer at a time, so the layer that
// reaches the cap can overshoot it; this keeps at most the cap's count while the mesh stays valid.
#pragma once
#include <cstdint>

#include "tokenizer/tokenizer.h"

namespace silk {

// At most max_faces faces of `mesh` (max_faces <= 0, or a mesh within it: unchanged): its faces
// in order, each kept unless it would give one of its corners a second fan (so every vertex
// keeps one fan), until max_faces are kept. Edge-manifoldness and orientation hold for any
// subset. Vertices no kept face uses and components left without faces are dropped (the rest
// renumbered in order).
TokenizerDecodedMesh CapFaces(const TokenizerDecodedMesh& mesh, int32_t max_faces);

}  // namespace silk
