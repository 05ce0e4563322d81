// SPDX-License-Identifier: MIT
// glTF 2.0 reader (.gltf JSON and .glb) through tinygltf, with our own validation before
// and after it: GLB container, JSON depth, external buffers, node graph, accessor bounds.
#pragma once
#include <string>
#include <string_view>

#include "core/status.h"
#include "io/io_mesh.h"
#include "io/read_options.h"

namespace silk {

// Reads the triangle primitives of the meshes reachable from the default scene (scene 0, or
// all root nodes when there are no scenes), with node transforms applied. `base_dir` is the
// folder external buffers are resolved against; when `from_memory` is true no external file
// is ever opened (fuzzing, in-memory inputs). Images are never loaded or decoded.
StatusOr<IoMesh> ReadGltf(std::string_view data, bool binary, const std::string& name, const std::string& base_dir,
                          bool from_memory, const ReadOptions& opts = {});

}  // namespace silk
