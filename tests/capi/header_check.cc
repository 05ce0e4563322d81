// SPDX-License-Identifier: MIT
// The public headers under the strictest flags a consumer may use: the capi_header_* ctests
// compile this file (syntax only) as C++17 with -Wall -Wextra -Wpedantic -Werror, once with silk.h
// alone and once with silk.hpp too (SILK_WITH_HPP); tests/capi/capi_c_compile.c is the C99 twin.
// Named .cc so the capi gtest executable does not pick it up.
#include "silk/silk.h"
#ifdef SILK_WITH_HPP
#include "silk/silk.hpp"
#endif

#if SILK_VERSION_NUMBER < 10000
#error "C API 1.0 or later expected"
#endif

int main() {
  silk_encode_stats st = silk_encode_stats();
  st.struct_size = sizeof st;
  silk_encode_params ep = silk_encode_default_params();
  silk_mesh* m = nullptr;
  silk_tokens* t = nullptr;
  size_t n = 0;
  if (silk_mesh_load("x.obj", nullptr, &m) != SILK_OK) return 1;
  if (silk_mesh_encode(m, &ep, &t, &st) != SILK_OK) return 2;
  if (silk_tokens_copy(t, nullptr, 0, &n) != SILK_OK) return 3;
  silk_report* r = nullptr;
  if (silk_generator_report(nullptr, 0, &r) == SILK_OK) return 4;
#ifdef SILK_WITH_HPP
  const silk_cpp::Mesh mesh = silk_cpp::Mesh::FromArrays({0, 0, 0, 1, 0, 0, 0, 1, 0}, {0, 1, 2});
  const std::vector<int32_t> ids = mesh.Encode().ids();
  const silk_vocab_info v = silk_cpp::Vocab();
  if (mesh.triangles().size() != 3 || mesh.vertex_count() != 3 || ids.empty() || v.eos_id < 0) return 5;
#endif
  silk_tokens_destroy(t);
  silk_mesh_destroy(m);
  return 0;
}
