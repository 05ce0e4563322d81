// SPDX-License-Identifier: MIT
// Non-manifold processing (token_format.md §3.2-§3.6): split vertices whose faces do not form a single
// fan, reproducing the reference's partition exactly (order emulation in
// reference_order_emulation).
#pragma once
#include <cstdint>

#include "core/status.h"
#include "tokenizer/processed_mesh.h"

namespace silk {

struct NonManifoldStats {
  int32_t nm_vertices = 0;
  int32_t copies = 0;
};

// mesh.positions: quantized positions by VertexId (copies are appended with the same QVec);
// mesh.faces: processed faces (after §2.4). Mutates corner ids in place (faces are never
// removed or reordered) and appends copies. Refusals per token_format.md §14.A.
Status SplitNonManifoldVertices(TokenizerProcessedMesh& mesh, NonManifoldStats* stats);

}  // namespace silk
