// SPDX-License-Identifier: MIT
// The generated mesh as the caller gets it: grid positions back into the input's frame, and the
// output's verdicts (edge-/vertex-manifold, watertight, oriented, open edges) into the stats.
#pragma once
#include "io/io_mesh.h"
#include "mesh/normalize.h"
#include "runtime/generator.h"

namespace silk {

// The one step from the generated mesh to the output (docs/mesh_types.md): grid positions ->
// [-1, 1] (tokenizer dequantisation) -> input frame (UndoNormalization); faces as decoded. The
// part index per triangle stays in decoded.face_component.
IoMesh ToInputFrame(const TokenizerDecodedMesh& decoded, const NormalizeTransform& transform);

// Edge-manifold / watertight / orientation verdicts and open edges of the output, into stats.
void FillVerdicts(const IoMesh& mesh, GenerationStats* stats);

// ToInputFrame + FillVerdicts into generation->stats.
IoMesh FinishOutput(GenerateResult* generation, const NormalizeTransform& transform);

}  // namespace silk
