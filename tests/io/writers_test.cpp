// SPDX-License-Identifier: MIT
// OBJ/PLY writers round-trip through the readers; atomic writes leave no partial output.
#include <gtest/gtest.h>

#include <sys/stat.h>

#include <filesystem>

#include "io/files/atomic_file.h"
#include "io/mesh_reader.h"
#include "io/obj/obj_writer.h"
#include "io/ply/ply_writer.h"
#include "io/io_test_util.h"

namespace silk {
namespace {

IoMesh Sample() {
  IoMesh m;
  m.positions = {{0.1, -2.5e-7, 1e300}, {1.0 / 3.0, 2, 3}, {-0.0, 5e-324, 123456789.123456789}};
  m.triangles = {{0, 1, 2}, {2, 1, 0}};
  return m;
}

TEST(ObjWriter, RoundTripsExactDoubles) {
  testing::TempDir dir;
  const std::string p = dir.path() + "/out.obj";
  ASSERT_TRUE(WriteObjFile(p, Sample()).ok());
  auto m = ReadMeshFile(p);
  ASSERT_TRUE(m.ok()) << m.status().ToString();
  EXPECT_EQ(m->positions, Sample().positions);
  EXPECT_EQ(m->triangles, Sample().triangles);
}

TEST(ObjWriter, IntegerCoordinates) {
  IoMesh m;
  m.positions = {{3, 64, 18}, {0, 127, -1}, {1, 1, 1}};
  m.triangles = {{0, 1, 2}};
  ObjWriteOptions opts;
  opts.integer_coordinates = true;
  auto text = FormatObj(m, opts);
  ASSERT_TRUE(text.ok());
  EXPECT_EQ(*text, "v 3 64 18\nv 0 127 -1\nv 1 1 1\nf 1 2 3\n");
  m.positions[0][0] = 3.5;
  EXPECT_FALSE(FormatObj(m, opts).ok());
}

TEST(ObjWriter, RejectsInvalidMeshWithoutWriting) {
  testing::TempDir dir;
  IoMesh m = Sample();
  m.triangles.push_back({0, 1, 3});
  const std::string p = dir.path() + "/bad.obj";
  Status s = WriteObjFile(p, m);
  ASSERT_FALSE(s.ok());
  EXPECT_NE(s.message().find("bad.obj: triangle 2: index 3 out of range (3 vertices)"), std::string::npos)
      << s.message();
  EXPECT_FALSE(std::filesystem::exists(p));
}

TEST(PlyWriter, BinaryLittleEndianRoundTrip) {
  testing::TempDir dir;
  const std::string p = dir.path() + "/out.ply";
  ASSERT_TRUE(WritePlyFile(p, Sample()).ok());
  auto m = ReadMeshFile(p);
  ASSERT_TRUE(m.ok()) << m.status().ToString();
  EXPECT_EQ(m->positions, Sample().positions);
  EXPECT_EQ(m->triangles, Sample().triangles);
  auto bytes = FormatPlyBinary(Sample());
  ASSERT_TRUE(bytes.ok());
  EXPECT_EQ(bytes->rfind("ply\nformat binary_little_endian 1.0\n", 0), 0u);
}

TEST(AtomicFile, ReplacesExistingFileAndLeavesNoTemp) {
  testing::TempDir dir;
  const std::string p = dir.Write("f.txt", "old");
  ASSERT_TRUE(WriteFileAtomically(p, "new contents").ok());
  std::ifstream in(p);
  std::string s((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_EQ(s, "new contents");
  int files = 0;
  for (const auto& e : std::filesystem::directory_iterator(dir.path())) {
    (void)e;
    ++files;
  }
  EXPECT_EQ(files, 1);
}

TEST(AtomicFile, FailureLeavesNothing) {
  testing::TempDir dir;
  // Target is an existing non-empty directory: rename fails after the temp file was written.
  const std::string target = dir.path() + "/sub";
  std::filesystem::create_directory(target);
  dir.Write("sub/keep", "x");
  Status s = WriteFileAtomically(target, "data");
  ASSERT_FALSE(s.ok());
  EXPECT_NE(s.message().find("sub"), std::string::npos);
  int files = 0;
  for (const auto& e : std::filesystem::directory_iterator(dir.path())) {
    (void)e;
    ++files;
  }
  EXPECT_EQ(files, 1);  // only "sub"; the temp file was removed
  Status missing = WriteFileAtomically(dir.path() + "/no/such/dir/f.obj", "data");
  EXPECT_FALSE(missing.ok());
  EXPECT_EQ(missing.code(), StatusCode::kIoError);
}

}  // namespace
}  // namespace silk
