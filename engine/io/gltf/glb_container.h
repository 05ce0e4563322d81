// SPDX-License-Identifier: MIT
// GLB container validation: the 12-byte header and the JSON/BIN chunk table, checked
// completely before tinygltf sees the bytes (tinygltf 2.7 trusts the BIN chunk length).
#pragma once
#include <string>
#include <string_view>

#include "core/status.h"

namespace silk {

struct GlbChunks {
  std::string_view json;
  std::string_view bin;  // empty when there is no BIN chunk
};

// Errors: "x.glb: not a GLB file (no 'glTF' magic)", bad version, chunk lengths past the end.
StatusOr<GlbChunks> ParseGlbContainer(std::string_view data, const std::string& name);

}  // namespace silk
