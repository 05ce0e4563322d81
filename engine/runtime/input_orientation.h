// SPDX-License-Identifier: MIT
// Generated parts turned to face the side the input's normals call outside (mesh/orient_to_points),
// in the model frame, where the grid mesh and the encoder's points meet.
#pragma once
#include <memory>
#include <vector>

#include "mesh/orient_to_points.h"
#include "tokenizer/tokenizer.h"

namespace silk {

// The encoder's points (rows of 6 floats: xyz, normal) as an oriented reference set.
std::shared_ptr<const OrientedPointSet> MakeInputOrientation(const std::vector<float>& points);

// Reverses every part of `mesh` (grid coordinates, face_component) whose area-weighted winding
// disagrees with the reference normals.
PartOrientationReport OrientToInput(TokenizerDecodedMesh* mesh, const OrientedPointSet& reference);

}  // namespace silk
