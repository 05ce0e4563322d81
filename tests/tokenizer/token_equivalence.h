// SPDX-License-Identifier: MIT
// Test helper: decides whether a candidate face set of one decoded component is
// token-equivalent to the input, by running the real encoder stages on it
// (EncodeProcessedMesh: non-manifold split, orientation, components, layering, codecs).
#pragma once
#include <array>
#include <cstdint>
#include <vector>

#include "face_compare.h"
#include "tokenizer/layering/layered_stream.h"

namespace silk::testing {

// Permutation putting `faces` in the order of `reference` (same corner set = same face; the
// rest keep their order, after). The encoder breaks face sort-key ties by input face order
// (§4.1), which the tokens do not carry, so an equivalence proof may choose the order: this
// one is the official encoder's.
std::vector<size_t> OrderLike(const std::vector<CoordFace>& faces, const std::vector<CoordFace>& reference);

// True when `faces` (vertex ids into `positions`, one decoded component) encode to exactly
// one component whose stream (positions, S/X/B tokens) equals `want`. Vertex identities are
// kept (no welding), as the decoder emits them.
bool ComponentReencodesTo(const std::vector<QVec>& positions, const std::vector<std::array<int32_t, 3>>& faces,
                          const std::vector<CoordFace>& order_reference, const StreamComponent& want);

}  // namespace silk::testing
