// SPDX-License-Identifier: MIT
// Appends one glTF mesh instance (all its triangle primitives, transformed) to an IoMesh,
// validating accessors against their buffers before reading a single element.
#pragma once
#include <string>

#include <tiny_gltf.h>

#include "core/status.h"
#include "io/gltf/gltf_scene_walk.h"
#include "io/io_mesh.h"
#include "io/read_options.h"

namespace silk {

// TRIANGLES, TRIANGLE_STRIP and TRIANGLE_FAN primitives are read (strips and fans converted
// to triangles as the glTF spec defines them); points/lines are skipped with a warning.
// Every vertex of the POSITION accessor is appended (unreferenced ones too). A transform
// with negative determinant flips the winding so the faces keep their outward side.
Status AppendGltfMeshInstance(const tinygltf::Model& model, const GltfMeshInstance& inst, const std::string& name,
                              const ReadOptions& opts, IoMesh* mesh);

}  // namespace silk
