// SPDX-License-Identifier: MIT
// Walks the glTF node graph of the scene to read and returns each mesh reference with its
// world transform. Iterative with a visited set: cycles (RecursiveNodes) and shared children
// are errors, never an endless loop or a stack overflow.
#pragma once
#include <array>
#include <string>
#include <vector>

#include <tiny_gltf.h>

#include "core/status.h"

namespace silk {

struct GltfMeshInstance {
  int mesh = -1;
  int node = -1;
  std::array<double, 16> matrix;  // column-major world transform, as glTF stores matrices
};

// Scene: model.defaultScene when set, else scene 0, else (no scenes) every root node.
StatusOr<std::vector<GltfMeshInstance>> CollectGltfMeshInstances(const tinygltf::Model& model, const std::string& name);

}  // namespace silk
