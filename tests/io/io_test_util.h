// SPDX-License-Identifier: MIT
// Helpers for the io tests: a temporary folder removed at the end of the test, writing test
// inputs (text or bytes) into it, and gzip-compressing them.
#pragma once
#include <stdlib.h>
#include <unistd.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#ifdef SILK_HAVE_ZLIB
#include <zlib.h>
#endif

namespace silk::testing {

#ifdef SILK_HAVE_ZLIB
// `data` as a gzip stream ("" if zlib fails, which the reading test then reports).
inline std::string Gzip(const std::string& data) {
  z_stream zs{};
  if (deflateInit2(&zs, 6, Z_DEFLATED, 15 + 16, 8, Z_DEFAULT_STRATEGY) != Z_OK) return "";
  std::string out(deflateBound(&zs, data.size()) + 64, '\0');
  zs.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(data.data()));
  zs.avail_in = static_cast<uInt>(data.size());
  zs.next_out = reinterpret_cast<Bytef*>(&out[0]);
  zs.avail_out = static_cast<uInt>(out.size());
  const bool ok = deflate(&zs, Z_FINISH) == Z_STREAM_END;
  out.resize(ok ? zs.total_out : 0);
  deflateEnd(&zs);
  return out;
}
#endif

class TempDir {
 public:
  TempDir() {
    std::string base = std::filesystem::temp_directory_path().string() + "/silk_io_XXXXXX";
    std::vector<char> buf(base.begin(), base.end());
    buf.push_back('\0');
#ifdef _WIN32  // no mkdtemp: _mktemp_s names it, create_directory refuses an existing one
    path_ = _mktemp_s(buf.data(), buf.size()) == 0 && std::filesystem::create_directory(buf.data())
                ? std::string(buf.data())
                : std::string();
#else
    path_ = mkdtemp(buf.data()) ? std::string(buf.data()) : std::string();
#endif
  }
  ~TempDir() {
    std::error_code ec;
    if (!path_.empty()) std::filesystem::remove_all(path_, ec);
  }
  const std::string& path() const { return path_; }
  std::string Write(const std::string& name, const std::string& bytes) const {
    std::string p = path_ + "/" + name;
    std::ofstream(p, std::ios::binary) << bytes;
    return p;
  }

 private:
  std::string path_;
};

// Little-endian / big-endian byte appenders for building binary inputs.
template <typename T>
void AppendLE(std::string* s, T v) {
  char b[sizeof(T)];
  std::memcpy(b, &v, sizeof(T));
  s->append(b, sizeof(T));
}
template <typename T>
void AppendBE(std::string* s, T v) {
  char b[sizeof(T)];
  std::memcpy(b, &v, sizeof(T));
  for (size_t i = sizeof(T); i-- > 0;) s->push_back(b[i]);
}

}  // namespace silk::testing
