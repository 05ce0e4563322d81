// SPDX-License-Identifier: MIT
// ReadMeshFile dispatch: extensions, ".gz" wrapping, content sniffing, file errors.
#include "io/mesh_reader.h"

#include <gtest/gtest.h>

#ifdef SILK_HAVE_ZLIB
#include <zlib.h>
#endif

#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <fstream>
#include <vector>

#include "io/io_test_util.h"

namespace silk {
namespace {

const char* kTriObj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";

#ifdef SILK_HAVE_ZLIB
using testing::Gzip;

TEST(MeshReader, GzipWrappedFormats) {
  testing::TempDir dir;
  auto m = ReadMeshFile(dir.Write("tri.obj.gz", Gzip(kTriObj)));
  ASSERT_TRUE(m.ok()) << m.status().ToString();
  EXPECT_EQ(m->triangles.size(), 1u);
  auto off = ReadMeshFile(dir.Write("tri.OFF.GZ", Gzip("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n")));
  ASSERT_TRUE(off.ok()) << off.status().ToString();
}

TEST(MeshReader, CorruptAndTruncatedGzip) {
  testing::TempDir dir;
  std::string gz = Gzip(std::string(kTriObj) + std::string(10000, '#'));
  auto t = ReadMeshFile(dir.Write("t.obj.gz", gz.substr(0, gz.size() / 2)));
  ASSERT_FALSE(t.ok());
  EXPECT_NE(t.status().message().find("t.obj.gz: truncated gzip data"), std::string::npos) << t.status().message();
  auto c = ReadMeshFile(dir.Write("c.obj.gz", "not gzip at all"));
  ASSERT_FALSE(c.ok());
  EXPECT_NE(c.status().message().find("c.obj.gz: not a gzip file"), std::string::npos);
}

TEST(MeshReader, GzipBombIsLimited) {
  testing::TempDir dir;
  ReadOptions opts;
  opts.max_file_bytes = 1 << 20;
  auto m = ReadMeshFile(dir.Write("bomb.obj.gz", Gzip(std::string(8 << 20, '#'))), opts);
  ASSERT_FALSE(m.ok());
  EXPECT_EQ(m.status().code(), StatusCode::kLimitExceeded);
}

// Streams a gzip file of `total` bytes of `fill` (1 MiB at a time, run-length deflate: fast).
std::string WriteGzipOfFill(const std::string& path, char fill, uint64_t total) {
  z_stream zs{};
  EXPECT_EQ(deflateInit2(&zs, 9, Z_DEFLATED, 15 + 16, 9, Z_RLE), Z_OK);
  const std::string chunk(size_t{1} << 20, fill);
  std::vector<char> out(size_t{1} << 20);
  std::ofstream f(path, std::ios::binary);
  for (uint64_t done = 0; done <= total;) {
    const bool last = done == total;
    zs.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(chunk.data()));
    zs.avail_in = last ? 0u : static_cast<uInt>(std::min<uint64_t>(chunk.size(), total - done));
    done += zs.avail_in;
    do {
      zs.next_out = reinterpret_cast<Bytef*>(out.data());
      zs.avail_out = static_cast<uInt>(out.size());
      deflate(&zs, last ? Z_FINISH : Z_NO_FLUSH);
      f.write(out.data(), static_cast<std::streamsize>(out.size() - zs.avail_out));
    } while (zs.avail_out == 0);
    if (last) break;
  }
  deflateEnd(&zs);
  return path;
}

long MaxRssKb() {
  rusage ru{};
  getrusage(RUSAGE_SELF, &ru);
  return ru.ru_maxrss;
}

// Issue 20, finding 5: a 600 KB .obj.gz of 600 MB of spaces is refused while inflating (default
// options), in bounded time and memory, with the file named; it used to inflate fully first.
TEST(MeshReader, GzipBombIsRefusedWhileInflating) {
  testing::TempDir dir;
  const std::string path = WriteGzipOfFill(dir.path() + "/bomb.obj.gz", ' ', uint64_t{600} << 20);
  const long rss_before = MaxRssKb();
  const auto t0 = std::chrono::steady_clock::now();
  auto m = ReadMeshFile(path);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  ASSERT_FALSE(m.ok());
  EXPECT_EQ(m.status().code(), StatusCode::kLimitExceeded) << m.status().ToString();
  EXPECT_NE(m.status().message().find(path + ": gzip data inflates past the limit of 67108864 bytes"),
            std::string::npos)
      << m.status().message();
  EXPECT_LT(seconds, 5.0);
  EXPECT_LT(MaxRssKb() - rss_before, 128 * 1024) << "peak RSS grew by " << (MaxRssKb() - rss_before) << " KB";
}

// The inflation cap is max(floor, ratio * compressed size), never above max_file_bytes: a
// well-compressing input passes the floor only when its .gz is large enough.
TEST(MeshReader, GzipInflatedLimitScalesWithCompressedSize) {
  ReadOptions opts;
  EXPECT_EQ(InflatedLimit(opts, 1000), uint64_t{64} << 20);
  EXPECT_EQ(InflatedLimit(opts, uint64_t{10} << 20), uint64_t{320} << 20);
  EXPECT_EQ(InflatedLimit(opts, uint64_t{1} << 30), opts.max_file_bytes);
  EXPECT_EQ(InflatedLimit(opts, UINT64_MAX), opts.max_file_bytes);
  opts.max_inflated_bytes = 1 << 20;
  testing::TempDir dir;
  std::string noise;  // incompressible comment bytes: ratio about 1
  uint32_t x = 12345;
  for (int i = 0; i < (2 << 20); ++i)
    noise.push_back(static_cast<char>('a' + ((x = x * 1103515245u + 12345u) >> 16) % 26));
  auto ok = ReadMeshFile(dir.Write("noisy.obj.gz", Gzip(kTriObj + ("# " + noise + "\n"))), opts);
  ASSERT_TRUE(ok.ok()) << ok.status().ToString();
  EXPECT_EQ(ok->triangles.size(), 1u);
  auto bomb = ReadMeshFile(dir.Write("small_bomb.obj.gz", Gzip(kTriObj + std::string(2 << 20, '#'))), opts);
  ASSERT_FALSE(bomb.ok());
  EXPECT_NE(bomb.status().message().find("small_bomb.obj.gz: gzip data inflates past the limit of 1048576 bytes"),
            std::string::npos)
      << bomb.status().message();
}

#endif  // SILK_HAVE_ZLIB

TEST(MeshReader, SniffsUnknownExtension) {
  testing::TempDir dir;
  auto m = ReadMeshFile(dir.Write("mesh.data", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"));
  ASSERT_TRUE(m.ok()) << m.status().ToString();
  auto u = ReadMeshFile(dir.Write("mesh.abc", kTriObj));  // (.xyz is a point-cloud format since issue 22)
  ASSERT_FALSE(u.ok());
  EXPECT_NE(u.status().message().find("mesh.abc: unknown mesh format"), std::string::npos);
}

TEST(MeshReader, MissingFileAndDirectory) {
  testing::TempDir dir;
  auto m = ReadMeshFile(dir.path() + "/nope.obj");
  ASSERT_FALSE(m.ok());
  EXPECT_EQ(m.status().code(), StatusCode::kIoError);
  EXPECT_NE(m.status().message().find("nope.obj: cannot open"), std::string::npos);
  auto d = ReadMeshFile(dir.path());
  ASSERT_FALSE(d.ok());
}

TEST(MeshReader, FromMemoryAllFormats) {
  const std::string obj = kTriObj;
  auto m = ReadMeshFromMemory(reinterpret_cast<const uint8_t*>(obj.data()), obj.size(), MeshFormat::kObj, "mem");
  ASSERT_TRUE(m.ok());
  auto e = ReadMeshFromMemory(nullptr, 0, MeshFormat::kPly, "empty.ply");
  ASSERT_FALSE(e.ok());
  EXPECT_NE(e.status().message().find("empty.ply"), std::string::npos);
}

}  // namespace
}  // namespace silk
