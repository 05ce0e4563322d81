// SPDX-License-Identifier: MIT
// Reading and encoding one mesh file for silktok through the public API, with errors that name
// the file.
#pragma once
#include <string>

#include "cli_errors.h"
#include "silk/silk.hpp"

namespace silktok {

// The file read as a mesh, as the tokenizer sees it (a PLY without faces too); errors name it.
silk_cpp::Mesh LoadMesh(const std::string& path);
// LoadMesh + silk_mesh_encode; the encoder's errors are prefixed with the file ("path: mobius: ...").
silk_cpp::Tokens LoadAndEncode(const std::string& path, const silk_encode_params& params,
                               silk_encode_stats* stats = nullptr);

}  // namespace silktok
