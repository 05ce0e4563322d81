// SPDX-License-Identifier: MIT
// Strict PLY reader (ascii, binary_little_endian, binary_big_endian): x/y/z of the "vertex"
// element and the "vertex_indices"/"vertex_index" list of the "face" element; all other
// properties and elements are parsed and skipped (ReadPlyPointCloud also reads nx/ny/nz).
#pragma once
#include <array>
#include <string>
#include <string_view>
#include <vector>

#include "core/status.h"
#include "io/io_mesh.h"
#include "io/io_point_cloud.h"
#include "io/read_options.h"

namespace silk {

// Header counts are checked against the bytes that follow the header before anything is
// allocated. A truncated body is an error naming the element and its index. Faces with more
// than 3 corners are fan-triangulated. Float32 values (also in ascii files) are rounded to
// float first, exactly as a binary file would store them.
StatusOr<IoMesh> ReadPly(std::string_view data, const std::string& name, const ReadOptions& opts = {});

// A PLY that may be a point cloud: faces optional, per-vertex normals (nx, ny, nz) read when
// the vertex element has all three (`normals` empty otherwise, else one per vertex).
using PlyPointCloud = IoPointCloud;
StatusOr<PlyPointCloud> ReadPlyPointCloud(std::string_view data, const std::string& name, const ReadOptions& opts = {});

}  // namespace silk
