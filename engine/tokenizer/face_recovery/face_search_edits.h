// SPDX-License-Identifier: MIT
// The verification search's moves (face_recovery.cpp): a candidate face set with its
// verification, and the elementary edits at one vertex that produce its neighbours.
#pragma once
#include <array>
#include <cstdint>
#include <vector>

#include "tokenizer/face_recovery/component_graph.h"
#include "tokenizer/face_recovery/face_growth.h"
#include "tokenizer/face_recovery/face_verification.h"

namespace silk {

struct SearchCandidate {
  GrowConstraints constraints;
  std::vector<int8_t> orient;  // per triangle of the graph (face_growth.h)
  std::vector<std::array<int32_t, 3>> faces;
  FaceVerification verification;
};

// Grows under `constraints` and verifies the result.
SearchCandidate EvaluateCandidate(const ComponentGraph& g, GrowConstraints constraints,
                                  FaceRecoveryStats* stats = nullptr);

// Adds to `c` (a copy of from.constraints) the regrowing edit of triangle t: variant 0 drops
// a face of `from` (forbidden) or imposes winding +1 on a triangle that is not one, variant 1
// flips the face (forces the other winding) or imposes winding -1.
void ApplyRegrowEdit(const ComponentGraph& g, const SearchCandidate& from, int32_t t, int variant, GrowConstraints* c);

// The single edits at vertex v of `from`, as growth constraints, per triangle at v: drop a
// face it has (regrow), flip it (force the other winding, regrow), drop it with nothing else
// changed (the growth would refill a real hole), impose a face it lacks in either winding
// (regrow), or add it in either winding with nothing else changed (a hole the growth left).
// Search growths get `lookahead_budget`. Appends to `out`.
void EditsAt(const ComponentGraph& g, const SearchCandidate& from, int32_t v, int64_t lookahead_budget,
             std::vector<GrowConstraints>* out);

}  // namespace silk
