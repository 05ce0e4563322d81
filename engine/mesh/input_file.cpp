// SPDX-License-Identifier: MIT
// Reading a generation input file and estimating a point cloud's missing normals.
#include "mesh/input_file.h"

#include <utility>

#include "io/point_cloud_reader.h"
#include "mesh/normal_estimation.h"

namespace silk {

StatusOr<IoPointCloud> ReadGenerationInputFile(const std::string& path, bool* normals_estimated,
                                               const ReadOptions& opts) {
  if (normals_estimated) *normals_estimated = false;
  SILK_ASSIGN_OR_RETURN(IoPointCloud in, ReadMeshOrPointCloudFile(path, opts));
  if (!in.mesh.triangles.empty() || !in.normals.empty()) return in;
  auto normals = EstimateNormals(in.mesh.positions);
  if (!normals.ok()) return normals.status().WithContext(path + ": a point cloud without normals: ");
  in.normals = std::move(*normals);
  if (normals_estimated) *normals_estimated = true;
  return in;
}

}  // namespace silk
