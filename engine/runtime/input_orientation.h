// SPDX-License-Identifier: MIT
// Generated parts turned to face the side the input's normals call outside (mesh/orient_to_points),
// in the model frame, where the grid mesh and the encoder's points meet.
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

// Reverses every part of `mesh` (grid coordinates, face_component) whose area-weighted winding
// disagrees with the reference normals.
PartOrientationReport OrientToInput(TokenizerDecodedMesh* mesh, const OrientedPointSet& reference);
// The same, polling `cancel` (kCancelled leaves the mesh as it was).
StatusOr<PartOrientationReport> OrientToInput(TokenizerDecodedMesh* mesh, const OrientedPointSet& reference,
                                              const CancelCheck& cancel);

}  // namespace silk
