// SPDX-License-Identifier: MIT
// The file rules every Silk tool inherits from libsilk's one reader and one writer (issue 35):
// only regular files are read (a FIFO, a device behind a symlink, a folder refused by type, at
// once), outputs go through a hidden temporary that a signal handler can remove, and a name the
// file system cannot hold is refused before any work.
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <string>

#include "io/files/atomic_file.h"
#include "io/files/file_bytes.h"
#include "io/files/output_path.h"
#include "io/files/partial_files.h"
#include "io/io_test_util.h"

#ifndef _WIN32
#include <sys/stat.h>
#include <unistd.h>
#endif

namespace silk {
namespace {

namespace fs = std::filesystem;

int CountFiles(const std::string& dir) {
  int n = 0;
  for (const auto& e : fs::directory_iterator(dir)) {
    (void)e;
    ++n;
  }
  return n;
}

#ifndef _WIN32
TEST(FileSafety, FifoIsRefusedWithoutBlocking) {
  testing::TempDir dir;
  const std::string fifo = dir.path() + "/pipe.obj";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  const auto t0 = std::chrono::steady_clock::now();
  StatusOr<std::string> r = ReadFileBytes(fifo, 1 << 20);  // blocked forever in open() before
  EXPECT_LT(std::chrono::steady_clock::now() - t0, std::chrono::seconds(2));
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().code(), StatusCode::kIoError);
  EXPECT_NE(r.status().message().find("pipe.obj"), std::string::npos) << r.status().message();
  EXPECT_NE(r.status().message().find("FIFO"), std::string::npos) << r.status().message();
}

TEST(FileSafety, SymlinkToDeviceIsRefusedBeforeReading) {
  testing::TempDir dir;
  const std::string link = dir.path() + "/zero.obj";
  fs::create_symlink("/dev/zero", link);
  StatusOr<std::string> r = ReadFileBytes(link, uint64_t{4} << 30);  // read 4 GiB of zeros before
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.status().message().find("character device"), std::string::npos) << r.status().message();
}
#endif

TEST(FileSafety, FolderIsRefused) {
  testing::TempDir dir;
  StatusOr<std::string> r = ReadFileBytes(dir.path(), 1 << 20);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.status().message().find("a folder"), std::string::npos) << r.status().message();
}

TEST(FileSafety, TemporaryIsHiddenBesideTheTarget) {
  EXPECT_EQ(TemporaryPathFor("out/chair.glb", 42, 0), "out/.chair.glb.tmp-42");
  EXPECT_EQ(TemporaryPathFor("chair.glb", 42, 3), ".chair.glb.tmp-42-3");
  const std::string long_name(250, 'n');
  const std::string tmp = TemporaryPathFor("d/" + long_name, 42, 0);
  EXPECT_EQ(tmp.rfind("d/.", 0), 0u) << tmp;
  EXPECT_LE(tmp.size() - 2, kTemporaryNameLimit);
}

TEST(FileSafety, LongestNameIsWritten) {
#ifdef _WIN32
  GTEST_SKIP() << "a 255-byte name under the temporary folder passes Windows' MAX_PATH: CheckOutputPath refuses "
                  "such a path up front (FileSafety.OutputPathChecks)";
#endif
  testing::TempDir dir;
  const std::string name = std::string(251, 'a') + ".glb";  // 255 bytes: failed on its temporary before
  ASSERT_TRUE(WriteFileAtomically(dir.path() + "/" + name, "x").ok());
  EXPECT_TRUE(fs::exists(dir.path() + "/" + name));
  EXPECT_EQ(CountFiles(dir.path()), 1);
}

TEST(FileSafety, OutputPathChecks) {
  testing::TempDir dir;
#ifdef _WIN32
  // Past MAX_PATH (260 UTF-16 units) without the \\?\ prefix: refused before any work, naming the limit.
  const Status past_max_path = CheckOutputPath(dir.path() + "/" + std::string(251, 'a') + ".glb");
  ASSERT_FALSE(past_max_path.ok());
  EXPECT_NE(past_max_path.message().find("MAX_PATH"), std::string::npos) << past_max_path.message();
#else
  EXPECT_TRUE(CheckOutputPath(dir.path() + "/" + std::string(251, 'a') + ".glb").ok());
#endif
  const Status too_long = CheckOutputPath(dir.path() + "/" + std::string(252, 'a') + ".glb");
  ASSERT_FALSE(too_long.ok());
  EXPECT_NE(too_long.message().find("256 bytes"), std::string::npos) << too_long.message();
  EXPECT_FALSE(CheckOutputPath(dir.path()).ok());
  EXPECT_FALSE(CheckOutputPath(dir.path() + "/").ok());
  EXPECT_EQ(CheckOutputPath(dir.path() + "/no/such/f.obj").code(), StatusCode::kIoError);
  EXPECT_FALSE(CheckOutputPath("").ok());
#ifdef _WIN32
  for (const char* name : {"CON", "nul.obj", "COM1.glb", "lpt9.tar.gz", "a?.obj", "trailing.obj."})
    EXPECT_FALSE(CheckOutputPath(dir.path() + "/" + name).ok()) << name;
#endif
  EXPECT_EQ(CountFiles(dir.path()), 0);  // nothing created
}

TEST(FileSafety, DiscardRemovesOnlyWritesInProgress) {
  testing::TempDir dir;
  const std::string open_tmp = dir.Write(".a.obj.tmp-1", "partial");
  const std::string done_tmp = dir.Write(".b.obj.tmp-1", "kept");
  const int open_slot = RegisterPartialFile(open_tmp);
  const int done_slot = RegisterPartialFile(done_tmp);
  ASSERT_GE(open_slot, 0);
  ASSERT_GE(done_slot, 0);
  ReleasePartialFile(done_slot);
  DiscardPartialFiles();
  EXPECT_FALSE(fs::exists(open_tmp));
  EXPECT_TRUE(fs::exists(done_tmp));
  ReleasePartialFile(open_slot);
}

}  // namespace
}  // namespace silk
