// SPDX-License-Identifier: MIT
// libFuzzer target for the PMD reader: arbitrary bytes through the io entry point must give a
// mesh with in-range indices or a Status, never a crash, hang or huge allocation.
#include <cstddef>
#include <cstdint>
#include <cstdlib>

#include "io/mesh_reader.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  silk::ReadOptions opts;
  opts.max_vertices = 1 << 20;
  opts.max_triangles = 1 << 20;
  auto mesh = silk::ReadMeshFromMemory(data, size, silk::MeshFormat::kPmd, "fuzz.pmd", opts);
  if (mesh.ok()) {
    for (const auto& t : mesh->triangles)
      for (int32_t i : t)
        if (i < 0 || static_cast<size_t>(i) >= mesh->positions.size()) std::abort();
  }
  return 0;
}
