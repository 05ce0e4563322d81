// Face recovery: the tokens carry vertices and edges only (spec §10.5); this rebuilds the
// oriented faces of one component from its layers and decoded edges (spec §10.6, improved).
#pragma once
#include <array>
#include <cstdint>
#include <vector>

#include "core/status.h"
#include "tokenizer/component_graph.h"

namespace silk {

struct FaceRecoveryStats {
  int32_t triangles = 0;          // 3-cycles of the edge graph (candidate faces)
  int32_t hint_faces = 0;         // faces suggested by the layer order
  int32_t forced = 0;             // faces accepted as the only candidate of an open edge
  int32_t resolved = 0;           // faces chosen among several candidates
  int32_t seeds = 0;              // face-connected regions started
  int32_t uncovered_edges = 0;    // edges left without any face
};

// Oriented faces of one component, corners = vertex ids in reading order within the
// component (layer 0's root = 0, then layer 1, ...). Works on any prefix of layers too
// (the grammar state machine calls it on partial components). Guarantees: every edge has
// at most 2 faces, no directed edge is used twice (consistent orientation), every face is a
// 3-cycle of the decoded edges. Winding follows the encoder's: the root's fan is
// (root, l_k, l_k+1). Bounded work; kLimitExceeded for pathological graphs,
// kInvalidArgument for shapes that do not fit (indices outside their layers).
StatusOr<std::vector<std::array<int32_t, 3>>> RecoverComponentFaces(const ComponentLayers& layers,
                                                                     FaceRecoveryStats* stats = nullptr);

// Same on an already built graph.
StatusOr<std::vector<std::array<int32_t, 3>>> RecoverFacesOfGraph(const ComponentGraph& g,
                                                                   FaceRecoveryStats* stats = nullptr);

}  // namespace silk
