// SPDX-License-Identifier: MIT
// One call that turns a read layer into its LayerAdjacency (self + between edges), for the
// decoder pipeline and for the grammar state machine, which decodes layer by layer.
#pragma once
#include <cstdint>

#include "core/status.h"
#include "tokenizer/layering/layered_stream.h"

namespace silk {

// `prev_size` = vertex count of the previous layer (1 for layer 1). Layer 0 has no
// adjacency; do not call this for it.
StatusOr<LayerAdjacency> DecodeLayerAdjacency(const StreamLayer& layer, int32_t prev_size);

}  // namespace silk
