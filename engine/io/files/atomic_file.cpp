// SPDX-License-Identifier: MIT
// mkstemp + write loop + fsync + rename, with cleanup on every failure path (Windows: a
// CreateFileW temp file + WriteFile + FlushFileBuffers + MoveFileExW replacing the target).
#include "io/files/atomic_file.h"

#ifdef _WIN32
#include <algorithm>
#include <atomic>

#include "core/windows_text.h"
#include "io/files/native_path.h"
#else
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <vector>
#endif

namespace silk {

#ifdef _WIN32
Status WriteFileAtomically(const std::string& path, const std::string& bytes) {
  if (path.empty()) return InvalidArgument("empty output path");
  static std::atomic<unsigned> counter{0};
  const std::wstring target = NativePath(path).wstring();
  const std::wstring tmp = target + L".tmp." + std::to_wstring(GetCurrentProcessId()) + L"." + std::to_wstring(counter++);
  HANDLE h = CreateFileW(tmp.c_str(), GENERIC_WRITE, 0, nullptr, CREATE_NEW, FILE_ATTRIBUTE_NORMAL, nullptr);
  if (h == INVALID_HANDLE_VALUE) return IoError(path + ": cannot create temporary file: " + WindowsErrorText(GetLastError()));
  auto fail = [&](const std::string& what) {
    const DWORD err = GetLastError();
    if (h != INVALID_HANDLE_VALUE) CloseHandle(h);
    DeleteFileW(tmp.c_str());
    return IoError(path + ": " + what + ": " + WindowsErrorText(err));
  };
  size_t done = 0;
  while (done < bytes.size()) {
    const DWORD chunk = static_cast<DWORD>(std::min<size_t>(bytes.size() - done, 1u << 30));
    DWORD wrote = 0;
    if (!WriteFile(h, bytes.data() + done, chunk, &wrote, nullptr)) return fail("write failed");
    done += wrote;
  }
  if (!FlushFileBuffers(h)) return fail("flush failed");
  const BOOL closed = CloseHandle(h);
  h = INVALID_HANDLE_VALUE;
  if (!closed) return fail("close failed");
  // NTFS semantics: std::rename does not replace an existing file there; MoveFileExW does, and
  // refuses (the old file intact) while another program holds the target open without sharing.
  if (!MoveFileExW(tmp.c_str(), target.c_str(), MOVEFILE_REPLACE_EXISTING | MOVEFILE_WRITE_THROUGH)) {
    const DWORD err = GetLastError();
    if (err == ERROR_SHARING_VIOLATION || err == ERROR_ACCESS_DENIED || err == ERROR_LOCK_VIOLATION) {
      SetLastError(err);
      return fail("cannot replace the file: it is open in another program or read-only (the old file is kept)");
    }
    SetLastError(err);
    return fail("rename failed");
  }
  return Status::Ok();
}
#else

namespace {
std::string DirOf(const std::string& path) {
  size_t slash = path.find_last_of('/');
  if (slash == std::string::npos) return ".";
  return slash == 0 ? "/" : path.substr(0, slash);
}
}  // namespace

Status WriteFileAtomically(const std::string& path, const std::string& bytes) {
  if (path.empty()) return InvalidArgument("empty output path");
  std::string tmpl = path + ".tmp.XXXXXX";
  std::vector<char> buf(tmpl.begin(), tmpl.end());
  buf.push_back('\0');
  int fd = ::mkstemp(buf.data());
  if (fd < 0) return IoError(path + ": cannot create temporary file: " + std::strerror(errno));
  const std::string tmp(buf.data());
  auto fail = [&](const std::string& what, int err) {
    if (fd >= 0) ::close(fd);
    ::unlink(tmp.c_str());
    return IoError(path + ": " + what + ": " + std::strerror(err));
  };
  size_t done = 0;
  while (done < bytes.size()) {
    ssize_t w = ::write(fd, bytes.data() + done, bytes.size() - done);
    if (w < 0) {
      if (errno == EINTR) continue;
      return fail("write failed", errno);
    }
    done += static_cast<size_t>(w);
  }
  // mkstemp creates 0600; give the file the usual permissions (umask applies).
  mode_t mask = ::umask(0);
  ::umask(mask);
  ::fchmod(fd, 0666 & ~mask);
  if (::fsync(fd) != 0) return fail("fsync failed", errno);
  if (::close(fd) != 0) {
    fd = -1;
    return fail("close failed", errno);
  }
  fd = -1;
  if (::rename(tmp.c_str(), path.c_str()) != 0) return fail("rename failed", errno);
  // Make the rename itself durable (best effort).
  int dfd = ::open(DirOf(path).c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (dfd >= 0) {
    ::fsync(dfd);
    ::close(dfd);
  }
  return Status::Ok();
}
#endif  // _WIN32

}  // namespace silk
