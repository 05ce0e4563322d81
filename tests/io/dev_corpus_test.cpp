// The 160 dev OBJ meshes: vertex and face counts must match corpus/dev/MANIFEST.tsv, and
// reading all of them must be fast.
#include <gtest/gtest.h>

#include <chrono>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "io/mesh_reader.h"
#include "support/test_paths.h"

namespace silk {
namespace {

std::vector<std::string> SplitTabs(const std::string& line) {
  std::vector<std::string> out;
  std::stringstream ss(line);
  std::string cell;
  while (std::getline(ss, cell, '\t')) out.push_back(cell);
  return out;
}

TEST(DevCorpus, CountsMatchManifest) {
  std::ifstream manifest(testing::SharedPath("corpus/dev/MANIFEST.tsv"));
  ASSERT_TRUE(manifest) << "MANIFEST.tsv not found";
  std::string line;
  ASSERT_TRUE(std::getline(manifest, line));
  const std::vector<std::string> header = SplitTabs(line);
  int col_file = -1, col_vertices = -1, col_faces = -1;
  for (size_t i = 0; i < header.size(); ++i) {
    if (header[i] == "file") col_file = static_cast<int>(i);
    if (header[i] == "vertices") col_vertices = static_cast<int>(i);
    if (header[i] == "faces") col_faces = static_cast<int>(i);
  }
  ASSERT_GE(col_file, 0);
  ASSERT_GE(col_vertices, 0);
  ASSERT_GE(col_faces, 0);
  int files = 0;
  double total_secs = 0;
  while (std::getline(manifest, line)) {
    if (line.empty()) continue;
    const std::vector<std::string> cells = SplitTabs(line);
    const std::string& file = cells.at(col_file);
    const auto t0 = std::chrono::steady_clock::now();
    auto m = ReadMeshFile(testing::SharedPath("corpus/dev/" + file));
    total_secs += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    ASSERT_TRUE(m.ok()) << m.status().ToString();
    EXPECT_EQ(m->positions.size(), std::stoull(cells.at(col_vertices))) << file;
    EXPECT_EQ(m->triangles.size(), std::stoull(cells.at(col_faces))) << file;
    ++files;
  }
  EXPECT_EQ(files, 160);
  std::printf("read %d dev meshes in %.3f s\n", files, total_secs);
  EXPECT_LT(total_secs, 10.0);  // ~0.2 s in a release build; generous for sanitizer builds
}

}  // namespace
}  // namespace silk
