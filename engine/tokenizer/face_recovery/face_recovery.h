// SPDX-License-Identifier: MIT
// Face recovery: the tokens carry vertices and edges only (token_format.md §10.5); this rebuilds the
// oriented faces of one component from its layers and decoded edges (token_format.md §10.6, improved).
#pragma once
#include <array>
#include <cstdint>
#include <vector>

#include "core/status.h"
#include "tokenizer/face_recovery/component_graph.h"
#include "tokenizer/face_recovery/face_recovery_stats.h"

namespace silk {

// Oriented faces of one component, corners = vertex ids in reading order within the
// component (layer 0's root = 0, then layer 1, ...). Works on any prefix of closed layers too
// (the grammar state machine calls it on partial components). Guarantees: every edge has
// at most 2 faces, no directed edge is used twice (consistent orientation), every face is a
// 3-cycle of the decoded edges. Winding follows the encoder's: the root's fan is
// (root, l_k, l_k+1). The growth heuristic's answer is verified by replaying the encoder's
// layering on it (face_verification.h); where that fails, a bounded local search changes
// faces at the first failing vertex. Bounded work; kLimitExceeded for pathological graphs,
// kInvalidArgument for shapes that do not fit (indices outside their layers).
StatusOr<std::vector<std::array<int32_t, 3>>> RecoverComponentFaces(const ComponentLayers& layers,
                                                                    FaceRecoveryStats* stats = nullptr);

// Same on an already built graph.
StatusOr<std::vector<std::array<int32_t, 3>>> RecoverFacesOfGraph(const ComponentGraph& g,
                                                                  FaceRecoveryStats* stats = nullptr);

}  // namespace silk
