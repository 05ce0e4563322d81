// SPDX-License-Identifier: MIT
// Test helper: maps the official processed faces of a golden onto one decoded component's
// graph by grid coordinates (faces with a coincident or absent corner, or an edge the graph
// lacks, are left out), so face_verification can score the truth.
#pragma once
#include <array>
#include <cstdint>
#include <vector>

#include "face_compare.h"
#include "tokenizer/face_recovery/component_graph.h"
#include "tokenizer/layering/layered_stream.h"

namespace silk::testing {

// Component layers of one stream component (the decoder's own input to face recovery).
ComponentLayers LayersOfComponent(const StreamComponent& comp);

// `faces` minus `excluded` (coordinate equality), mapped to vertex ids of g.
std::vector<std::array<int32_t, 3>> TruthOnGraph(const ComponentGraph& g, const std::vector<CoordFace>& faces,
                                                 const std::vector<CoordFace>& excluded);

}  // namespace silk::testing
