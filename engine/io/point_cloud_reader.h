// SPDX-License-Identifier: MIT
// Reading a file that may be a point cloud (a PLY without faces, an XYZ/PTS file) as well as a
// mesh: what a generation input is loaded with (silk_mesh_load), as against ReadMeshFile, the
// tokenizer's view, for which a file without faces is an error.
#pragma once
#include <string>

#include "core/status.h"
#include "io/io_point_cloud.h"
#include "io/read_options.h"

namespace silk {

// By extension, a ".gz" wrapper allowed: .ply is read with ReadPlyPointCloud (faces optional,
// nx/ny/nz read when present), .xyz/.pts with ReadXyz, anything else with ReadMeshFile. The
// result is a point cloud when it has no triangles (its normals empty when the file has none);
// a mesh comes back without normals (a PLY mesh's per-vertex normals are not used).
StatusOr<IoPointCloud> ReadMeshOrPointCloudFile(const std::string& path, const ReadOptions& opts = {});

}  // namespace silk
