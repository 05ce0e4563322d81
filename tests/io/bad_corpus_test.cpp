// SPDX-License-Identifier: MIT
// Every file of corpus/bad: a clear error naming the file and the problem (read times printed;
// a hang fails by the ctest timeout). The two cases whose problem is only visible after
// cleaning (degenerate / duplicate faces) must read raw here; the mesh layer rejects them later.
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <map>
#include <string>

#include "io/mesh_reader.h"
#include "support/test_paths.h"

namespace silk {
namespace {

struct Expectation {
  bool reads_raw;       // reader succeeds (cleaning happens in a later layer)
  std::string message;  // substring of the error message, after "<path>"
};

const std::map<std::string, Expectation>& Table() {
  static const std::map<std::string, Expectation> t = {
      {"empty.obj", {false, ": empty file"}},
      {"nan_coords.obj", {false, ":3: vertex 2 has a non-finite coordinate 'nan'"}},
      {"index_out_of_range.obj", {false, ":7: face index 5 out of range (4 vertices)"}},
      {"truncated_body.ply", {false, ": truncated body: face 6 of 12 ends past the end of the file"}},
      {"degenerate_only.obj", {true, ""}},
      {"dup_faces_2M.ply.gz", {true, ""}},
      {"cube_obj_text.glb", {false, ": not a GLB file (no 'glTF' magic)"}},
      {"garbage_bytes.obj", {false, ":1: "}},
      {"assimp_OutOfMemory.off", {false, ":2: header says 353535235358 vertices and 6 faces but only 14 data lines"}},
      {"assimp_invalid.off", {false, ":6: face 0 has 0 corner(s), at least 3 needed"}},
      {"assimp_issue623.ply", {false, ":13: vertex 0: missing value for property 'vertex_indices'"}},
      {"assimp_IndexOutOfRange.gltf", {false, ": mesh 0 primitive 0: index 255 (at 0) out of range (24 vertices)"}},
      {"assimp_BoxWithInfinites.glb", {false, ": mesh 0 primitive 0: POSITION 0 is not finite"}},
      {"assimp_RecursiveNodes.gltf", {false, ": node graph is not a tree: node 0 is reached twice"}},
      {"assimp_MissingBin.gltf", {false, ": buffer 0: external file 'BoxTextured0.bin' not found"}},
  };
  return t;
}

TEST(BadCorpus, EveryFileFailsCleanly) {
  const std::string dir = testing::SharedPath("corpus/bad");
  int checked = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    const std::string file = entry.path().filename().string();
    if (file == "README.md" || file == "IndexOutOfRange.bin") continue;  // docs / data of a case
    auto it = Table().find(file);
    ASSERT_NE(it, Table().end()) << "new bad-corpus file without an expectation: " << file;
    const std::string path = entry.path().string();
    const auto t0 = std::chrono::steady_clock::now();
    auto m = ReadMeshFile(path);
    const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::printf("%-28s %6.3f s  %s\n", file.c_str(), secs, m.ok() ? "read (raw)" : m.status().ToString().c_str());
    if (it->second.reads_raw) {
      EXPECT_TRUE(m.ok()) << m.status().ToString();
    } else {
      ASSERT_FALSE(m.ok()) << file << " was accepted";
      EXPECT_NE(m.status().message().find(file), std::string::npos) << m.status().message();
      EXPECT_NE(m.status().message().find(path + it->second.message), std::string::npos)
          << "message:  " << m.status().message() << "\nexpected: " << path + it->second.message;
    }
    ++checked;
  }
  EXPECT_EQ(checked, static_cast<int>(Table().size()));
}

TEST(BadCorpus, DegenerateOnlyReadsRaw) {
  auto m = ReadMeshFile(testing::SharedPath("corpus/bad/degenerate_only.obj"));
  ASSERT_TRUE(m.ok());
  EXPECT_EQ(m->positions.size(), 5u);
  EXPECT_EQ(m->triangles.size(), 5u);  // zero-area faces are kept; cleaning is not the reader's job
}

TEST(BadCorpus, DuplicateFaces2MReadsThroughGzip) {
  const auto t0 = std::chrono::steady_clock::now();
  auto m = ReadMeshFile(testing::SharedPath("corpus/bad/dup_faces_2M.ply.gz"));
  const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  ASSERT_TRUE(m.ok()) << m.status().ToString();
  EXPECT_EQ(m->positions.size(), 3u);
  ASSERT_EQ(m->triangles.size(), 2000000u);
  EXPECT_EQ(m->triangles.front(), m->triangles.back());
  std::printf("dup_faces_2M.ply.gz read in %.3f s\n", secs);
}

}  // namespace
}  // namespace silk
