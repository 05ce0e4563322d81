// SPDX-License-Identifier: MIT
// Quantization, vertex merging and face cleanup (token_format.md §2.2-§2.4): the first encoder stage,
// turning a normalised IoMesh into the TokenizerProcessedMesh every later stage works on.
#pragma once
#include "core/status.h"
#include "io/io_mesh.h"
#include "tokenizer/processed_mesh.h"

namespace silk {

struct CleanupStats {
  int32_t merged_vertices = 0;   // vertices that are duplicates of an earlier one (§2.3)
  int32_t degenerate_faces = 0;  // repeated corner or collinear (§2.4 steps 2-3)
  int32_t duplicate_faces = 0;   // same corner set as an earlier face (§2.4 step 4)
};

// Positions must be finite; indices are validated (out of range -> InvalidArgument).
StatusOr<TokenizerProcessedMesh> QuantizeAndClean(const IoMesh& normalized, CleanupStats* stats);

}  // namespace silk
