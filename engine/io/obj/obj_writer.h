// SPDX-License-Identifier: MIT
// OBJ output: "v x y z" lines then 1-based "f a b c" lines. Doubles are written in the
// shortest form that reads back to the same value.
#pragma once
#include <string>

#include "core/status.h"
#include "io/io_mesh.h"

namespace silk {

struct ObjWriteOptions {
  // Coordinates that are whole numbers (e.g. quantized grid positions held as doubles) are
  // written as integers ("v 3 64 18"); a non-integral coordinate is then an error.
  bool integer_coordinates = false;
  std::string header_comment;  // optional, written as "# ..." lines
};

StatusOr<std::string> FormatObj(const IoMesh& mesh, const ObjWriteOptions& opts = {});
Status WriteObjFile(const std::string& path, const IoMesh& mesh, const ObjWriteOptions& opts = {});

}  // namespace silk
