// SPDX-License-Identifier: MIT
// Checks a mesh is writable: finite coordinates and every triangle index in range. Writers
// call it so that no file is produced from an inconsistent mesh.
#pragma once
#include "core/status.h"
#include "io/io_mesh.h"

namespace silk {

Status ValidateOutputMesh(const IoMesh& mesh);

}  // namespace silk
