// SPDX-License-Identifier: MIT
// Binary little-endian PLY output: double x/y/z vertices (exact), uchar/int face lists.
#pragma once
#include <string>

#include "core/status.h"
#include "io/io_mesh.h"

namespace silk {

struct PlyWriteOptions {
  bool float32_coordinates = false;  // write "float" instead of "double" coordinates
};

StatusOr<std::string> FormatPlyBinary(const IoMesh& mesh, const PlyWriteOptions& opts = {});
Status WritePlyFile(const std::string& path, const IoMesh& mesh, const PlyWriteOptions& opts = {});

}  // namespace silk
