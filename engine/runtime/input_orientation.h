// SPDX-License-Identifier: MIT
// Generated surface patches turned to face the side the input's normals call outside
// (mesh/orient_to_points), in the model frame, where the grid mesh and the encoder's points meet.
#pragma once
#include <memory>
#include <vector>

#include "core/cancel_check.h"
#include "core/status.h"
#include "mesh/orient_to_points.h"
#include "tokenizer/tokenizer.h"

namespace silk {

// The encoder's points (rows of 6 floats: xyz, normal) as an oriented reference set; indexing a
// million points takes ~0.5 s, so `cancel` is polled (kCancelled).
StatusOr<std::shared_ptr<const OrientedPointSet>> MakeInputOrientation(const std::vector<float>& points,
                                                                       const CancelCheck& cancel = {});

// The surface patches of `mesh`: faces joined by shared edges, the unit whose winding the grammar
// keeps consistent. A generated part (face_component) may hold several (its decoded faces need not
// join all its vertices), and nothing ties their windings together. Returns each face's patch;
// *count: how many.
std::vector<int32_t> SurfacePatches(const TokenizerDecodedMesh& mesh, int32_t* count);

// Reverses every surface patch of `mesh` (grid coordinates) whose area-weighted winding disagrees
// with the reference normals.
PartOrientationReport OrientToInput(TokenizerDecodedMesh* mesh, const OrientedPointSet& reference);
// The same, polling `cancel` (kCancelled leaves the mesh as it was).
StatusOr<PartOrientationReport> OrientToInput(TokenizerDecodedMesh* mesh, const OrientedPointSet& reference,
                                              const CancelCheck& cancel);

}  // namespace silk
