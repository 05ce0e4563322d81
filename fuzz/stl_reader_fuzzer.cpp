// SPDX-License-Identifier: MIT
// libFuzzer target: arbitrary bytes through the STL reader (ReadMeshFromMemory, no files).
#include <cstddef>
#include <cstdint>

#include "fuzz_reader_common.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  return silk::fuzz::FuzzReadMesh(data, size, silk::MeshFormat::kStl, "fuzz.stl");
}
