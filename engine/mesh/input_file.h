// SPDX-License-Identifier: MIT
// A file as a generation input (what silk_mesh_load gives silkgen, the Python module and the
// add-on): a mesh, or a point cloud with one normal per point, its own or, for a cloud exported
// without normals, estimated here (mesh/normal_estimation). The one place that decides it.
#pragma once
#include <string>

#include "core/status.h"
#include "io/io_point_cloud.h"
#include "io/read_options.h"

namespace silk {

// ReadMeshOrPointCloudFile, then: a point cloud (no triangles) without normals gets
// EstimateNormals' (kDefaultNormalNeighbors), and *normals_estimated (may be null) says so; a
// cloud that carries normals keeps them exactly as read. Errors name the file.
StatusOr<IoPointCloud> ReadGenerationInputFile(const std::string& path, bool* normals_estimated = nullptr,
                                               const ReadOptions& opts = {});

}  // namespace silk
