// Helpers for the io tests: a temporary folder removed at the end of the test, and writing
// test inputs (text or bytes) into it.
#pragma once
#include <stdlib.h>
#include <unistd.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace silk::testing {

class TempDir {
 public:
  TempDir() {
    std::string base = std::filesystem::temp_directory_path().string() + "/silk_io_XXXXXX";
    std::vector<char> buf(base.begin(), base.end());
    buf.push_back('\0');
#ifdef _WIN32  // no mkdtemp: _mktemp_s names it, create_directory refuses an existing one
    path_ = _mktemp_s(buf.data(), buf.size()) == 0 && std::filesystem::create_directory(buf.data())
                ? std::string(buf.data()) : std::string();
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
