// SPDX-License-Identifier: MIT
// libFuzzer target: arbitrary bytes as a silkgen --batch list file (apps/silkgen/batch_list.h).
// Each kept line is a usable path: non-empty, within kMaxListLineBytes, no control byte, no blank
// at either end, not a comment, and found in the input as written; each refused line has a
// printable, bounded excerpt and a reason naming its line; line numbers ascend; nothing passes
// the entry limit.
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "batch_list.h"

namespace {

bool HasControlByte(std::string_view s) {
  for (char ch : s) {
    const unsigned char c = static_cast<unsigned char>(ch);
    if (c < 0x20 || c == 0x7f) return true;
  }
  return false;
}

void CheckEntry(const silkgen::ListEntry& e, std::string_view text) {
  if (e.problem.empty()) {
    if (e.entry.empty() || e.entry.size() > silkgen::kMaxListLineBytes || HasControlByte(e.entry) ||
        e.entry[0] == '#' || e.entry.front() == ' ' || e.entry.back() == ' ')
      __builtin_trap();
    if (text.find(e.entry) == std::string_view::npos) __builtin_trap();
  } else {
    if (e.entry.size() > 203 || HasControlByte(e.entry)) __builtin_trap();
    if (e.problem.rfind("list line " + std::to_string(e.line) + " ", 0) != 0) __builtin_trap();
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  std::vector<silkgen::ListEntry> entries;
  std::string error;
  const bool ok = silkgen::ParseList(text, &entries, &error);
  if (!ok && error.empty()) __builtin_trap();
  if (entries.size() > silkgen::kMaxListEntries) __builtin_trap();
  size_t last_line = 0;
  for (const silkgen::ListEntry& e : entries) {
    if (e.line <= last_line) __builtin_trap();
    last_line = e.line;
    CheckEntry(e, text);
  }
  return 0;
}
