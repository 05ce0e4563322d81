// SPDX-License-Identifier: MIT
// Counters face recovery reports (growth and verification search), shared by their files.
#pragma once
#include <cstdint>

namespace silk {

struct FaceRecoveryStats {
  int32_t triangles = 0;           // 3-cycles of the edge graph (candidate faces)
  int32_t hint_faces = 0;          // faces suggested by the layer order
  int32_t forced = 0;              // faces accepted as the only candidate of an open edge
  int32_t resolved = 0;            // faces chosen among several candidates
  int32_t seeds = 0;               // face-connected regions started
  int32_t uncovered_edges = 0;     // edges left without any face
  int32_t verify_failures = 0;     // verification defects of the returned set (0 = replays exactly)
  int32_t search_evaluations = 0;  // candidate face sets grown and verified by the search
  int32_t pair_evaluations = 0;    // of which by the pairwise step (two edits at once)
  bool search_budget_exhausted = false;
};

}  // namespace silk
