// SPDX-License-Identifier: MIT
// The 160 dev OBJ meshes: vertex and face counts must match corpus/dev/MANIFEST.tsv (the read
// time is printed; speed targets live in bench/).
#include <gtest/gtest.h>

#include <chrono>
#include <string>

#include "io/mesh_reader.h"
#include "support/golden_files.h"
#include "support/test_paths.h"

namespace silk {
namespace {

TEST(DevCorpus, CountsMatchManifest) {
  const auto rows = testing::ReadTsvRows(testing::SharedPath("corpus/dev/MANIFEST.tsv"));
  ASSERT_FALSE(rows.empty()) << "MANIFEST.tsv not found or empty";
  int files = 0;
  double total_secs = 0;
  for (const auto& row : rows) {
    ASSERT_TRUE(row.count("file") && row.count("vertices") && row.count("faces")) << "MANIFEST.tsv columns";
    const std::string& file = row.at("file");
    const auto t0 = std::chrono::steady_clock::now();
    auto m = ReadMeshFile(testing::SharedPath("corpus/dev/" + file));
    total_secs += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    ASSERT_TRUE(m.ok()) << m.status().ToString();
    EXPECT_EQ(m->positions.size(), std::stoull(row.at("vertices"))) << file;
    EXPECT_EQ(m->triangles.size(), std::stoull(row.at("faces"))) << file;
    ++files;
  }
  EXPECT_EQ(files, 160);
  std::printf("read %d dev meshes in %.3f s\n", files, total_secs);
}

}  // namespace
}  // namespace silk
