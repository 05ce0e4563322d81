// SPDX-License-Identifier: MIT
// Compares a decoded mesh with the encoder's processed mesh (the exactness target):
// representable faces recovered, reversed windings, missing and extra faces.
#pragma once
#include <array>
#include <cstdint>
#include <vector>

#include "tokenizer/tokenizer.h"

namespace silk {

struct RoundTripReport {
  int64_t processed_faces = 0;      // faces of the emitted components
  int64_t representable_faces = 0;  // processed minus unencodable (token_format.md §5.4)
  int64_t recovered = 0;            // representable faces decoded with the encoder's winding
  int64_t reversed = 0;             // representable faces decoded with the opposite winding
  int64_t missing = 0;              // representable faces not decoded at all
  int64_t extra = 0;                // decoded faces that are not processed faces
  int64_t extra_unencodable = 0;    // decoded faces that are unencodable processed faces
  bool exact() const { return missing == 0 && reversed == 0; }
};

// Faces are compared by grid coordinates and cyclic corner order.
RoundTripReport CompareRoundTrip(const EncodeResult& encoded, const TokenizerDecodedMesh& decoded);

}  // namespace silk
