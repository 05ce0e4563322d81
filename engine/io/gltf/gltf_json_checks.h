// SPDX-License-Identifier: MIT
// Checks on the glTF JSON text that run before tinygltf parses it: nesting depth (tinygltf
// recurses on "extras") and external buffer files (missing file = clean error naming it).
#pragma once
#include <string>
#include <string_view>

#include "core/status.h"

namespace silk {

// Error when arrays/objects nest deeper than max_depth, or the text is not valid JSON.
Status CheckGltfJsonText(std::string_view json, const std::string& name, int max_depth = 64);

// Every buffer with a non-data URI must name an existing file under base_dir. When
// from_memory is true no external file may be used at all.
Status CheckGltfExternalBuffers(std::string_view json, const std::string& name, const std::string& base_dir,
                                bool from_memory);

// %XX decoding as glTF URIs use it.
std::string DecodeUriPercent(const std::string& uri);

}  // namespace silk
