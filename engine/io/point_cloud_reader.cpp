// SPDX-License-Identifier: MIT
// Dispatch of the files that may hold a point cloud (PLY, XYZ/PTS); the rest is ReadMeshFile.
#include "io/point_cloud_reader.h"

#include <new>

#include "io/mesh_format.h"
#include "io/mesh_reader.h"
#include "io/ply/ply_reader.h"
#include "io/read_error.h"
#include "io/xyz/xyz_reader.h"

namespace silk {

namespace {

StatusOr<IoPointCloud> ReadCloudBytes(const std::string& path, MeshFormat fmt, const ReadOptions& opts) {
  SILK_ASSIGN_OR_RETURN(std::string bytes, ReadInputFileBytes(path, opts));
  try {
    if (fmt == MeshFormat::kXyz) return ReadXyz(bytes, path, opts);
    SILK_ASSIGN_OR_RETURN(IoPointCloud pc, ReadPlyPointCloud(bytes, path, opts));
    if (!pc.mesh.triangles.empty()) pc.normals.clear();
    return pc;
  } catch (const std::bad_alloc&) {
    return LimitErrorIn(path, "out of memory");
  }
}

}  // namespace

StatusOr<IoPointCloud> ReadMeshOrPointCloudFile(const std::string& path, const ReadOptions& opts) {
  const auto fmt = MeshFormatFromPath(path);
  if (fmt == MeshFormat::kPly || fmt == MeshFormat::kXyz) return ReadCloudBytes(path, *fmt, opts);
  IoPointCloud pc;
  SILK_ASSIGN_OR_RETURN(pc.mesh, ReadMeshFile(path, opts));
  return pc;
}

}  // namespace silk
