// SPDX-License-Identifier: MIT
// Oriented growth, the heuristic core of face recovery (token_format.md §10.6, improved): faces are
// accepted one open edge at a time, forced choices first, layer-order hints next, a local rule last.
#pragma once
#include <array>
#include <cstdint>
#include <vector>

#include "tokenizer/face_recovery/component_graph.h"
#include "tokenizer/face_recovery/face_recovery_stats.h"

namespace silk {

// Decisions imposed on the growth by the verification search (face_recovery.cpp).
struct GrowConstraints {
  // Oriented faces placed before anything else, in order; one that no longer fits is skipped.
  std::vector<std::array<int32_t, 3>> forced;
  // Per triangle id of the graph (empty = none): never accepted.
  std::vector<char> forbidden;
  // Place the forced faces and nothing else (the search's direct edits of a face set).
  bool only_forced = false;
  // Steps the look-ahead may spend (bounds one growth on arbitrary graphs).
  int64_t lookahead_budget = int64_t{1} << 26;
};

// Orientation per triangle of g: +1 = face (c0, c1, c2), -1 = face (c0, c2, c1), 0 = not a
// face. Every edge gets at most 2 faces and no directed edge is used twice.
std::vector<int8_t> GrowFaces(const ComponentGraph& g, const GrowConstraints& constraints,
                              FaceRecoveryStats* stats = nullptr);

// The faces of an orientation vector, in triangle order.
std::vector<std::array<int32_t, 3>> FacesOfOrientation(const ComponentGraph& g, const std::vector<int8_t>& orient);

}  // namespace silk
