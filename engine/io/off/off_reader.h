// SPDX-License-Identifier: MIT
// Strict OFF reader ("OFF", also the COFF/NOFF/CNOFF/STOFF variants whose extra per-vertex
// values are ignored). One vertex or face record per line; '#' starts a comment.
#pragma once
#include <string>
#include <string_view>

#include "core/status.h"
#include "io/io_mesh.h"
#include "io/read_options.h"

namespace silk {

// The header counts are checked against the number of data lines that follow before
// anything is allocated. Faces with more than 3 corners are fan-triangulated.
StatusOr<IoMesh> ReadOff(std::string_view text, const std::string& name, const ReadOptions& opts = {});

}  // namespace silk
