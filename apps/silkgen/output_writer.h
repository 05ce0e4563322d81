// Writing the generated mesh by the output's extension: .glb (one node per part, smooth
// normals, optional per-part colours), .obj, .ply. Every write is atomic.
#pragma once
#include <string>

#include "core/status.h"
#include "runtime/generate_pipeline.h"

namespace silkgen {

// Extension check before any work is done ("" if fine, else the error message).
std::string CheckOutputPath(const std::string& path);
silk::Status WriteGeneratedMesh(const std::string& path, const silk::GeneratedMesh& mesh, bool part_colors);

}  // namespace silkgen
