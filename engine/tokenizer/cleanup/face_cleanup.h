// Quantization, vertex merging and face cleanup (token_format.md §2.2-§2.4): the first encoder stage,
// turning a normalised RawMesh into the ProcessedMesh every later stage works on.
#pragma once
#include "core/status.h"
#include "io/raw_mesh.h"
#include "tokenizer/processed_mesh.h"

namespace silk {

struct CleanupStats {
  int32_t merged_vertices = 0;   // vertices that are duplicates of an earlier one (§2.3)
  int32_t degenerate_faces = 0;  // repeated corner or collinear (§2.4 steps 2-3)
  int32_t duplicate_faces = 0;   // same corner set as an earlier face (§2.4 step 4)
};

// Positions must be finite; indices are validated (out of range -> InvalidArgument).
StatusOr<ProcessedMesh> QuantizeAndClean(const RawMesh& normalized, CleanupStats* stats);

}  // namespace silk
