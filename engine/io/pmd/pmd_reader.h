// SPDX-License-Identifier: MIT
// 0 A.D. PMD reader (binary "PSMD" model, versions 1-4): the game's art meshes are a large
// real-world corpus for the tokenizer. Keeps positions and triangles only, raw (no welding).
#pragma once
#include <string>
#include <string_view>

#include "core/status.h"
#include "io/io_mesh.h"
#include "io/read_options.h"

namespace silk {

// Strict: the whole file must parse (vertices, faces, bones, prop points) and end exactly
// where its header's data size says. Counts are checked against the remaining bytes before
// anything is allocated. Normals, UVs, bone weights and prop points are read and dropped.
StatusOr<IoMesh> ReadPmd(std::string_view data, const std::string& name, const ReadOptions& opts = {});

}  // namespace silk
