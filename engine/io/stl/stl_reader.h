// SPDX-License-Identifier: MIT
// STL reader, ascii and binary. Binary is recognised by its size (84 + 50 * n bytes) even
// when the 80-byte header starts with "solid". Every triangle adds 3 new vertices (raw).
#pragma once
#include <string>
#include <string_view>

#include "core/status.h"
#include "io/io_mesh.h"
#include "io/read_options.h"

namespace silk {

StatusOr<IoMesh> ReadStl(std::string_view data, const std::string& name, const ReadOptions& opts = {});

}  // namespace silk
