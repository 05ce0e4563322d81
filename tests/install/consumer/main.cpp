// SPDX-License-Identifier: MIT
// Consumer of an installed libsilk: encodes a tetrahedron, and (when the install can
// generate) generates from it with the model folder given on the command line.
#include <cstdio>

#include "silk/silk.hpp"

int main(int argc, char** argv) {
  try {
    const std::vector<double> xyz = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
    const std::vector<int32_t> tri = {0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3};
    silk_cpp::Mesh mesh = silk_cpp::Mesh::FromArrays(xyz, tri);
    const size_t n_tokens = mesh.Encode().ids().size();
    std::printf("silk %s: tetrahedron -> %zu tokens\n", silk_version(), n_tokens);
    if (n_tokens == 0) return 1;
    if (SILK_HAS_GENERATION_AT_CONFIGURE != silk_generation_available()) return 1;
    if (argc > 1 && silk_generation_available()) {
      silk_model_params mo = silk_model_default_params();
      mo.threads = 1;
      silk_cpp::Model model = silk_cpp::Model::Load(argv[1], mo);
      silk_cpp::Generator gen(model);
      silk_generate_params p = silk_generate_default_params();
      p.max_tokens = 120;
      silk_generate_stats st = silk_cpp::Sized<silk_generate_stats>();
      silk_cpp::Mesh out = gen.Generate(mesh, p, &st);
      std::printf("generated %lld ids -> %d faces\n", static_cast<long long>(st.tokens), st.faces);
      if (st.faces <= 0 || out.triangles().size() != 3u * st.faces) return 1;
    }
    return 0;
  } catch (const silk_cpp::Error& e) {
    std::fprintf(stderr, "consumer: %s\n", e.what());
    return 1;
  }
}
