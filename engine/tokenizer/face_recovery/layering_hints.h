// SPDX-License-Identifier: MIT
// Faces the layer order itself reveals (token_format.md §5.2-5.3): a vertex u of layer L-1 appends its
// next-layer run to layer L in rotation order, so two consecutive layer-L vertices that u
// introduced are corners of the face (u, x_k, x_k+1) with exactly that winding.
#pragma once
#include <array>
#include <cstdint>
#include <vector>

#include "tokenizer/face_recovery/component_graph.h"

namespace silk {

// Oriented faces (u, x_k, x_{k+1}) where u = the first previous-layer neighbour of both
// x_k and x_{k+1} (their introducer under the usual single-run case) and all three edges
// exist; layer 1 gives the root's fan. In reading order. These are strong hints, not facts:
// a second run or an unencoded edge can make one wrong.
std::vector<std::array<int32_t, 3>> LayeringHintFaces(const ComponentGraph& g);

}  // namespace silk
