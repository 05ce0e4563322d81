// SPDX-License-Identifier: MIT
// Counts, arrays and reports of C API handles through silk.h's size query and silk_report (the
// *_count functions and the report copy are gone in C API 1.0), so the capi tests read them one way.
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "silk/silk.h"

namespace silk::testing {

inline size_t TokenCount(const silk_tokens* t) {
  size_t n = 0;
  silk_tokens_copy(t, nullptr, 0, &n);
  return n;
}
inline std::vector<int32_t> TokenIds(const silk_tokens* t) {
  std::vector<int32_t> ids(TokenCount(t));
  size_t n = 0;
  if (!ids.empty()) silk_tokens_copy(t, ids.data(), ids.size(), &n);
  return ids;
}
inline size_t VertexCount(const silk_mesh* m) {
  size_t n = 0;
  silk_mesh_copy_positions(m, nullptr, 0, &n);
  return n / 3;
}
inline size_t TriangleCount(const silk_mesh* m) {
  size_t n = 0;
  silk_mesh_copy_triangles(m, nullptr, 0, &n);
  return n / 3;
}

// silk_generator_report's JSON text (the report destroyed after the copy).
inline silk_status GeneratorReport(silk_generator* g, int32_t trace, std::string* json) {
  silk_report* r = nullptr;
  const silk_status s = silk_generator_report(g, trace, &r);
  *json = r ? silk_report_json(r) : "";
  silk_report_destroy(r);
  return s;
}

}  // namespace silk::testing
