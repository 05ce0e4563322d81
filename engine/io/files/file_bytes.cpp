// SPDX-License-Identifier: MIT
// Whole-file reading through POSIX read(2), size checked with fstat before allocating
// (Windows: the same calls of MinGW's C runtime, the file opened by its UTF-16 path in binary mode).
#include "io/files/file_bytes.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "io/files/native_path.h"

namespace silk {

StatusOr<std::string> ReadFileBytes(const std::string& path, uint64_t max_bytes) {
#ifdef _WIN32
  int fd = ::_wopen(NativePath(path).c_str(), _O_RDONLY | _O_BINARY);
#else
  int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
#endif
  if (fd < 0) return IoError(path + ": cannot open: " + std::strerror(errno));
  struct stat st;
  if (::fstat(fd, &st) != 0) {
    int e = errno;
    ::close(fd);
    return IoError(path + ": cannot stat: " + std::strerror(e));
  }
  if (S_ISDIR(st.st_mode)) {
    ::close(fd);
    return IoError(path + ": is a directory");
  }
  if (static_cast<uint64_t>(st.st_size) > max_bytes) {
    ::close(fd);
    return LimitExceeded(path + ": file is " + std::to_string(st.st_size) + " bytes, limit " + std::to_string(max_bytes));
  }
  std::string out;
  out.resize(static_cast<size_t>(st.st_size));
  size_t got = 0;
  while (true) {
    if (got == out.size()) {
      if (!S_ISREG(st.st_mode) && out.size() < max_bytes) out.resize(std::min<uint64_t>(max_bytes, out.size() * 2 + 4096));
      else break;
    }
    ssize_t r = ::read(fd, &out[got], out.size() - got);
    if (r < 0) {
      if (errno == EINTR) continue;
      int e = errno;
      ::close(fd);
      return IoError(path + ": read failed: " + std::strerror(e));
    }
    if (r == 0) break;
    got += static_cast<size_t>(r);
  }
  ::close(fd);
  out.resize(got);
  return out;
}

}  // namespace silk
