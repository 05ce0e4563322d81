// SPDX-License-Identifier: MIT
// The generated valid fuzz seeds (fuzz/corpus/*_reader_fuzzer/cube*) must read as cubes through
// the file dispatcher, so the reader fuzzers start from inputs that reach deep into every reader.
// (The token fuzzers' seeds are token arrays, not meshes.)
#include <gtest/gtest.h>

#include <filesystem>

#include "io/mesh_reader.h"
#include "support/test_paths.h"

namespace silk {
namespace {

TEST(FuzzSeeds, ValidCubeSeedsRead) {
  int n = 0;
  for (const auto& e : std::filesystem::recursive_directory_iterator(testing::SourcePath("fuzz/corpus"))) {
    const std::string file = e.path().filename().string();
    if (!e.is_regular_file() || file.rfind("cube", 0) != 0 || file == "cube_obj_text.glb") continue;
    const std::string dir = e.path().parent_path().filename().string();
    if (dir.size() < 14 || dir.compare(dir.size() - 14, 14, "_reader_fuzzer") != 0) continue;
    auto m = ReadMeshFile(e.path().string());
    if (file == "cube_cycle.gltf") {
      ASSERT_FALSE(m.ok());
      EXPECT_NE(m.status().message().find("node graph is not a tree"), std::string::npos);
      continue;
    }
    ASSERT_TRUE(m.ok()) << m.status().ToString();
    EXPECT_GE(m->triangles.size(), 12u) << file;
    ++n;
  }
  EXPECT_GE(n, 10);
}

}  // namespace
}  // namespace silk
