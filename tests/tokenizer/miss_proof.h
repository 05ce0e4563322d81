// Test helper: lists the representable faces a decode misses or reverses, and proves which
// of them the tokens cannot determine (their component's decoded faces re-encode to the
// component's stream, token_equivalence.h), so tests exempt only what is computed here.
#pragma once
#include <array>
#include <cstdint>
#include <set>
#include <vector>

#include "face_compare.h"
#include "tokenizer/layered_stream.h"

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
std::vector<char> ComponentsReencoding(const DecodedMesh& mesh, const LayeredStream& stream,
                                       const std::vector<CoordFace>& order_reference);

// Decoded components holding all three corners of f (by grid coordinates).
std::set<int32_t> ComponentsAtCorners(const DecodedMesh& mesh, const CoordFace& f);

// f is proven undetermined by the tokens: some component holds its corners and every such
// component re-encodes to its stream.
bool MissIsProvenAmbiguous(const DecodedMesh& mesh, const std::vector<char>& reencoding, const CoordFace& f);

}  // namespace silk::testing
