// SPDX-License-Identifier: MIT
// Fixed slots of temporary-file paths (partial_files.h): a slot is claimed with a compare-exchange,
// filled, then published; the signal-time discard reads only published slots and calls unlink.
#include "io/files/partial_files.h"

#include <atomic>
#include <cstring>

#ifdef _WIN32
#include <cstdio>
#include <cwchar>

#include "io/files/native_path.h"
#else
#include <unistd.h>
#endif

namespace silk {
namespace {

constexpr int kSlots = 64;
constexpr size_t kPathBytes = 4352;  // PATH_MAX and a temporary suffix

// state: 0 free, 1 being filled, 2 published.
struct Slot {
  std::atomic<int> state{0};
#ifdef _WIN32
  wchar_t path[kPathBytes];
#else
  char path[kPathBytes];
#endif
};

Slot g_slots[kSlots];

}  // namespace

int RegisterPartialFile(const std::string& path) {
#ifdef _WIN32
  const std::wstring native = NativePath(path).wstring();
  if (native.size() >= kPathBytes) return -1;
#else
  if (path.size() >= kPathBytes) return -1;
#endif
  for (int i = 0; i < kSlots; ++i) {
    int expected = 0;
    if (!g_slots[i].state.compare_exchange_strong(expected, 1)) continue;
#ifdef _WIN32
    std::wmemcpy(g_slots[i].path, native.c_str(), native.size() + 1);
#else
    std::memcpy(g_slots[i].path, path.c_str(), path.size() + 1);
#endif
    g_slots[i].state.store(2);
    return i;
  }
  return -1;
}

void ReleasePartialFile(int slot) {
  if (slot >= 0 && slot < kSlots) g_slots[slot].state.store(0);
}

void DiscardPartialFiles() {
  for (Slot& s : g_slots) {
    if (s.state.load() != 2) continue;
#ifdef _WIN32
    _wunlink(s.path);
#else
    ::unlink(s.path);
#endif
  }
}

}  // namespace silk
