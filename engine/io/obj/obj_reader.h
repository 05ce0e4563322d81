// SPDX-License-Identifier: MIT
// Strict Wavefront OBJ reader: positions ("v") and faces ("f", any of the v, v/vt, v//vn,
// v/vt/vn forms, 1-based or negative relative indices). Everything else is ignored.
#pragma once
#include <string>
#include <string_view>

#include "core/status.h"
#include "io/io_mesh.h"
#include "io/read_options.h"

namespace silk {

// `name` is used in error messages ("bad.obj:3: face index 5 out of range (4 vertices)").
// Polygons with more than 3 corners are fan-triangulated; vertex order is file order;
// nothing is welded or removed. A face may only use vertices defined above it.
StatusOr<IoMesh> ReadObj(std::string_view text, const std::string& name, const ReadOptions& opts = {});

}  // namespace silk
