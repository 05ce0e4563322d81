// SPDX-License-Identifier: MIT
// Test helper: lists the representable faces a decode misses or reverses, and proves which
// of them the tokens cannot determine (their component's decoded faces re-encode to the
// component's stream, token_equivalence.h), so tests exempt only what is computed here.
#pragma once
#include <array>
#include <cstdint>
#include <set>
#include <vector>

#include "face_compare.h"
#include "tokenizer/layering/layered_stream.h"

namespace silk::testing {

struct MissedFace {
  CoordFace face;  // as in the target
  bool reversed;   // decoded with the opposite winding (else not decoded at all)
};

// processed minus unencodable (same corners in the same cyclic order).
std::vector<CoordFace> RepresentableFaces(const std::vector<CoordFace>& processed,
                                          const std::vector<CoordFace>& unencodable);

// Target faces not decoded with their winding (same corners, same cyclic order).
std::vector<MissedFace> MissedFaces(const std::vector<CoordFace>& decoded, const std::vector<CoordFace>& target);

// Per decoded component: its faces re-encode to stream.components[c] (faces ordered like
// `order_reference`, the official encoder's processed faces).
std::vector<char> ComponentsReencoding(const TokenizerDecodedMesh& mesh, const LayeredStream& stream,
                                       const std::vector<CoordFace>& order_reference);

// Decoded components holding all three corners of f (by grid coordinates).
std::set<int32_t> ComponentsAtCorners(const TokenizerDecodedMesh& mesh, const CoordFace& f);

// f is proven undetermined by the tokens: some component holds its corners and every such
// component re-encodes to its stream.
bool MissIsProvenAmbiguous(const TokenizerDecodedMesh& mesh, const std::vector<char>& reencoding, const CoordFace& f);

// Components with unencodable faces (§5.4): the real mesh holds faces the tokens cannot carry
// (they still sit in the rotation lists), so no decoded face set re-encodes to the stream
// alone. For each decoded component touched by an unencodable face (a corner at the grid
// coordinate of one of its vertices), those faces are mapped to its vertex ids by grid
// coordinate and added both to our decoded faces and to the official processed faces of the component;
// each set is re-encoded (ComponentReencodesTo). The component is not checked when the
// mapping is ambiguous: a touching face has a corner coordinate held by two vertices of the
// component, or has a corner outside it. (Their edges need not be in the component graph,
// unlike TruthOnGraph: the tokens mostly do not carry them.)
struct AugmentedReencoding {
  std::vector<char> checked;      // per component: touched by unencodable faces, mapping unambiguous
  std::vector<char> truth_equal;  // official faces + unencodable re-encode to the stream (soundness)
  std::vector<char> ours_equal;   // decoded faces + unencodable re-encode to the stream
};
AugmentedReencoding ComponentsReencodingWithUnencodable(const TokenizerDecodedMesh& mesh, const LayeredStream& stream,
                                                        const std::vector<CoordFace>& processed,
                                                        const std::vector<CoordFace>& unencodable,
                                                        const std::vector<CoordFace>& order_reference);

}  // namespace silk::testing
