// SPDX-License-Identifier: MIT
// A hidden temporary beside the target (".<name>.tmp-<pid>", created exclusively) + write loop +
// fsync + rename, with cleanup on every failure path and the temporary registered for removal by
// a signal handler (Windows: CreateFileW + WriteFile + FlushFileBuffers + MoveFileExW).
#include "io/files/atomic_file.h"

#include <string>

#include "io/files/output_path.h"
#include "io/files/partial_files.h"

#ifdef _WIN32
#include <algorithm>

#include "core/windows_text.h"
#include "io/files/native_path.h"
#else
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#endif

namespace silk {

// ".<name>.tmp-<pid>" beside `path` (attempt > 0 appends "-<attempt>", for a name already taken);
// a name too long to hold the suffix gets the short ".silk.tmp-<pid>-<attempt>" instead, so every
// name the file system holds can be written.
std::string TemporaryPathFor(const std::string& path, unsigned long pid, unsigned attempt) {
  const size_t slash = path.find_last_of(
#ifdef _WIN32
      "/\\:"
#else
      "/"
#endif
  );
  const std::string dir = slash == std::string::npos ? "" : path.substr(0, slash + 1);
  const std::string name = slash == std::string::npos ? path : path.substr(slash + 1);
  std::string suffix = ".tmp-" + std::to_string(pid);
  if (attempt > 0) suffix += "-" + std::to_string(attempt);
  if (1 + name.size() + suffix.size() <= kTemporaryNameLimit) return dir + "." + name + suffix;
  return dir + ".silk" + suffix + (attempt > 0 ? "" : "-0");
}

#ifdef _WIN32
Status WriteFileAtomically(const std::string& path, const std::string& bytes) {
  SILK_RETURN_IF_ERROR(CheckOutputPath(path));
  const std::wstring target = NativePath(path).wstring();
  std::wstring tmp;
  HANDLE h = INVALID_HANDLE_VALUE;
  for (unsigned attempt = 0; attempt < 100 && h == INVALID_HANDLE_VALUE; ++attempt) {
    tmp = NativePath(TemporaryPathFor(path, GetCurrentProcessId(), attempt)).wstring();
    h = CreateFileW(tmp.c_str(), GENERIC_WRITE, 0, nullptr, CREATE_NEW, FILE_ATTRIBUTE_HIDDEN, nullptr);
    if (h == INVALID_HANDLE_VALUE && GetLastError() != ERROR_FILE_EXISTS) break;
  }
  if (h == INVALID_HANDLE_VALUE)
    return IoError(path + ": cannot create temporary file: " + WindowsErrorText(GetLastError()));
  const int slot = RegisterPartialFile(Utf8Path(std::filesystem::path(tmp)));
  auto fail = [&](const std::string& what) {
    const DWORD err = GetLastError();
    if (h != INVALID_HANDLE_VALUE) CloseHandle(h);
    DeleteFileW(tmp.c_str());
    ReleasePartialFile(slot);
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
  SetFileAttributesW(target.c_str(), FILE_ATTRIBUTE_NORMAL);
  ReleasePartialFile(slot);
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
  SILK_RETURN_IF_ERROR(CheckOutputPath(path));
  std::string tmp;
  int fd = -1;
  for (unsigned attempt = 0; attempt < 100 && fd < 0; ++attempt) {
    tmp = TemporaryPathFor(path, static_cast<unsigned long>(::getpid()), attempt);
    fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC | O_NOFOLLOW, 0600);
    if (fd < 0 && errno != EEXIST) break;
  }
  if (fd < 0) return IoError(path + ": cannot create temporary file: " + std::strerror(errno));
  const int slot = RegisterPartialFile(tmp);
  auto fail = [&](const std::string& what, int err) {
    if (fd >= 0) ::close(fd);
    ::unlink(tmp.c_str());
    ReleasePartialFile(slot);
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
  // Created 0600; give the file the usual permissions (umask applies).
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
  ReleasePartialFile(slot);
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
