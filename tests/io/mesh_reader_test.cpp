// ReadMeshFile dispatch: extensions, ".gz" wrapping, content sniffing, file errors.
#include "io/mesh_reader.h"

#include <gtest/gtest.h>

#ifdef SILK_HAVE_ZLIB
#include <zlib.h>
#endif

#include "io/io_test_util.h"

namespace silk {
namespace {

const char* kTriObj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";

#ifdef SILK_HAVE_ZLIB
std::string Gzip(const std::string& data) {
  z_stream zs{};
  EXPECT_EQ(deflateInit2(&zs, 6, Z_DEFLATED, 15 + 16, 8, Z_DEFAULT_STRATEGY), Z_OK);
  std::string out(deflateBound(&zs, data.size()) + 64, '\0');
  zs.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(data.data()));
  zs.avail_in = static_cast<uInt>(data.size());
  zs.next_out = reinterpret_cast<Bytef*>(&out[0]);
  zs.avail_out = static_cast<uInt>(out.size());
  EXPECT_EQ(deflate(&zs, Z_FINISH), Z_STREAM_END);
  out.resize(zs.total_out);
  deflateEnd(&zs);
  return out;
}

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

#endif  // SILK_HAVE_ZLIB

TEST(MeshReader, SniffsUnknownExtension) {
  testing::TempDir dir;
  auto m = ReadMeshFile(dir.Write("mesh.data", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"));
  ASSERT_TRUE(m.ok()) << m.status().ToString();
  auto u = ReadMeshFile(dir.Write("mesh.xyz", kTriObj));
  ASSERT_FALSE(u.ok());
  EXPECT_NE(u.status().message().find("mesh.xyz: unknown mesh format"), std::string::npos);
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
