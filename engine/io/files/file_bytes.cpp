// SPDX-License-Identifier: MIT
// Whole-file reading through POSIX read(2), size checked with fstat before allocating
// (Windows: the same calls of MinGW's C runtime, the file opened by its UTF-16 path in binary mode).
// Only regular files are read: a FIFO, device, socket or folder (a symlink to /dev/zero included)
// is refused by its type before it is opened, and again on the opened descriptor, which is opened
// non-blocking so a FIFO swapped in between cannot block the open.
#include "io/files/file_bytes.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "io/files/native_path.h"

namespace silk {
namespace {

const char* KindOf(unsigned mode) {
  if (S_ISDIR(mode)) return "a folder";
#ifdef S_ISFIFO
  if (S_ISFIFO(mode)) return "a FIFO (named pipe)";
#endif
#ifdef S_ISSOCK
  if (S_ISSOCK(mode)) return "a socket";
#endif
  if (S_ISCHR(mode)) return "a character device";
#ifdef S_ISBLK
  if (S_ISBLK(mode)) return "a block device";
#endif
  return "not a regular file";
}

Status NotRegular(const std::string& path, unsigned mode) {
  return IoError(path + ": is " + KindOf(mode) + ", not a regular file (only regular files are read)");
}

}  // namespace

Status CheckRegularFile(const std::string& path, uint64_t* size) {
#ifdef _WIN32
  struct _stat64 st;
  if (::_wstat64(NativePath(path).c_str(), &st) != 0) return IoError(path + ": cannot open: " + std::strerror(errno));
#else
  struct stat st;
  if (::stat(path.c_str(), &st) != 0) return IoError(path + ": cannot open: " + std::strerror(errno));
#endif
  if (!S_ISREG(st.st_mode)) return NotRegular(path, st.st_mode);
  if (size) *size = static_cast<uint64_t>(st.st_size);
  return Status::Ok();
}

StatusOr<std::string> ReadFileBytes(const std::string& path, uint64_t max_bytes) {
  SILK_RETURN_IF_ERROR(CheckRegularFile(path));
#ifdef _WIN32
  int fd = ::_wopen(NativePath(path).c_str(), _O_RDONLY | _O_BINARY);
#else
  int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK | O_NOCTTY);
#endif
  if (fd < 0) return IoError(path + ": cannot open: " + std::strerror(errno));
  struct stat st;
  if (::fstat(fd, &st) != 0) {
    int e = errno;
    ::close(fd);
    return IoError(path + ": cannot stat: " + std::strerror(e));
  }
  if (!S_ISREG(st.st_mode)) {  // swapped for something else since the check above
    ::close(fd);
    return NotRegular(path, st.st_mode);
  }
  if (static_cast<uint64_t>(st.st_size) > max_bytes) {
    ::close(fd);
    return LimitExceeded(path + ": file is " + std::to_string(st.st_size) + " bytes, limit " +
                         std::to_string(max_bytes));
  }
  std::string out;
  out.resize(static_cast<size_t>(st.st_size));
  size_t got = 0;
  while (got < out.size()) {  // a file that shrank meanwhile ends early; one that grew is read to its old size
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
