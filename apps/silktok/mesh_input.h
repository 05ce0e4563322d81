// Reading and encoding one mesh file for silktok through the public API, and silktok's one
// error format ("silktok: <kind>: <file>: <problem>").
#pragma once
#include <string>

#include "silk/silk.hpp"

namespace silktok {

// The file read as a mesh, as the tokenizer sees it (a PLY without faces too); errors name it.
silk_cpp::Mesh LoadMesh(const std::string& path);
// LoadMesh + silk_encode; the encoder's errors are prefixed with the file ("path: mobius: ...").
silk_cpp::Tokens LoadAndEncode(const std::string& path, const silk_encode_params& params,
                               silk_encode_stats* stats = nullptr);
// The same error with `prefix` in front of its message (what() keeps "<kind>: " first).
silk_cpp::Error WithContext(const silk_cpp::Error& e, const std::string& prefix);
// An error silktok itself detects (a folder it cannot create), in the library's format.
silk_cpp::Error AppError(silk_status status, const std::string& message);
// "silktok: <kind>: <message>" on stderr.
void ReportError(const silk_cpp::Error& e);

}  // namespace silktok
