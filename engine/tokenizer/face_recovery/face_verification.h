// SPDX-License-Identifier: MIT
// Exact check of a candidate face set against the decoded layers: rebuilds the rotation
// lists the encoder would derive from those faces (token_format.md §4.1, §4.4, §5.1) and replays the
// first-run layering (§5.2-§5.3) layer by layer against the decoded layers.
#pragma once
#include <array>
#include <climits>
#include <cstdint>
#include <vector>

#include "tokenizer/face_recovery/component_graph.h"

namespace silk {

struct FaceVerification {
  // Vertices whose replayed run (or rotation list) disagrees with the decoded layers. A
  // vertex's run depends only on its own faces, so each defect is local to its faces.
  int32_t bad_runs = 0;
  int32_t uncovered_edges = 0;  // decoded edges without any candidate face
  // Vertices whose faces should change, in the order the replay met them (a run defect
  // names the vertex and the previous contributor of the same layer; then uncovered edges).
  std::vector<int32_t> suspects;
  // Where the first defect is: the failing vertex id for a run defect, vertex_count + the
  // lower end for an uncovered edge, INT32_MAX for none. Later is better at equal score.
  int32_t first_defect = INT32_MAX;
  int32_t Score() const { return bad_runs + uncovered_edges; }
  // Strictly better: fewer defects, or as many with the first one later.
  bool BetterThan(const FaceVerification& o) const {
    return Score() < o.Score() || (Score() == o.Score() && first_defect > o.first_defect);
  }
};

// `faces` are oriented 3-cycles of g (vertex ids of g). Checks the runs of every vertex of
// layers 0..last-1, so a prefix of closed layers is checked as far as it goes. Layers are
// replayed independently (visited = the decoded earlier layers), so one defect does not
// spoil the rest. Face sort-key ties (§4.1) make a vertex's start face ambiguous: any tied
// start that reproduces the layer is accepted. A decoded edge into the expected layer
// vertex that lies in no 3-cycle (no face can hold it, §5.4) counts one defect and keeps the
// layer aligned, without naming a suspect. Work O(faces log faces + vertices + edges).
FaceVerification VerifyComponentFaces(const ComponentGraph& g, const std::vector<std::array<int32_t, 3>>& faces);

}  // namespace silk
