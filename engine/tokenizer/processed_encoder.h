// SPDX-License-Identifier: MIT
// Encoder stages after cleanup (token_format.md §3-§7) on an already quantized face set: lets a decoder
// check prove that a candidate face set re-encodes to the very same tokens. Private to the tokenizer
// and its tests (tests/tools/check_layers.py).
#pragma once
#include "core/status.h"
#include "tokenizer/layering/layered_stream.h"
#include "tokenizer/processed_mesh.h"

namespace silk {

// Runs the non-manifold split, orientation repair, components, rotation lists, layering and
// the matrix codecs exactly as EncodeMesh does after its cleanup stage, on `mesh` (vertex
// ids as given: nothing is welded). Face order breaks the §4.1 sort-key ties, as in EncodeMesh.
StatusOr<LayeredStream> EncodeProcessedMesh(TokenizerProcessedMesh mesh);

}  // namespace silk
