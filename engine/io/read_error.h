// SPDX-License-Identifier: MIT
// Error-message helpers shared by the readers: every message starts with the file name and,
// when known, the line ("bad.obj:3: face index 5 out of range (4 vertices)").
#pragma once
#include <cstdint>
#include <string>

#include "core/status.h"

namespace silk {

inline Status ParseErrorAt(const std::string& name, int64_t line, const std::string& what) {
  return ParseError(name + ":" + std::to_string(line) + ": " + what);
}
inline Status ParseErrorIn(const std::string& name, const std::string& what) { return ParseError(name + ": " + what); }
inline Status LimitErrorIn(const std::string& name, const std::string& what) {
  return LimitExceeded(name + ": " + what);
}

// The index check's wording the OFF, PLY and PMD readers share after their own prefix
// ("face 2: vertex index 9 out of range (4 vertices)").
inline std::string VertexIndexOutOfRange(int64_t index, uint64_t vertex_count) {
  return "vertex index " + std::to_string(index) + " out of range (" + std::to_string(vertex_count) + " vertices)";
}

}  // namespace silk
