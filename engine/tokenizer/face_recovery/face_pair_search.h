// SPDX-License-Identifier: MIT
// Two simultaneous edits for the verification search: some defects need changes at two
// vertices at once (each alone scores no better), e.g. both faces of one edge replaced.
#pragma once
#include <cstdint>

#include "tokenizer/face_recovery/component_graph.h"
#include "tokenizer/face_recovery/face_search_edits.h"

namespace silk {

// Tries pairs of regrowing edits (face_search_edits.h: drop, flip or impose) on two
// triangles sharing an edge, the first at one of the first suspects of `cur` (at least one
// of the two a face of `cur`). Spends at most *evaluations_left grow+verify passes
// (decremented). True and *out = the best set found, from the first suspect that gives any
// set strictly better than `cur` (FaceVerification::BetterThan).
bool FindImprovingPair(const ComponentGraph& g, const SearchCandidate& cur, int64_t lookahead_budget,
                       int32_t* evaluations_left, SearchCandidate* out);

}  // namespace silk
