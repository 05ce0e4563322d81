// SPDX-License-Identifier: MIT
// silkgen --batch's list file parser: text in, one entry per line out, each line checked on its
// own. A list comes from pipelines and untrusted sources, so a line is refused (a failed row with
// the reason, the rest still run) rather than guessed at: a NUL byte (the OS would open a shorter
// path than the one reported), another control character, or more bytes than a path may have.
// Pure string work, no file system (fuzz/batch_list_fuzzer.cpp).
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace silkgen {

// Longest list line taken as a path (PATH_MAX on Linux); longer lines are refused.
constexpr size_t kMaxListLineBytes = 4096;
// Most entries in one list (the whole list is refused beyond: split it).
constexpr size_t kMaxListEntries = 1000000;
// Largest list file read.
constexpr uint64_t kMaxListBytes = uint64_t{128} << 20;

struct ListEntry {
  std::string entry;    // the line as written, trimmed; for a refused line a printable excerpt
  std::string problem;  // "" or why the line is refused ("line 3: holds a NUL byte at byte 5")
  size_t line = 0;      // 1-based
};

// Lines of `text`: '#' comment lines and blank lines skipped, spaces around a line and a CR before
// the LF dropped. False with a message when the list has more than kMaxListEntries entries.
// Work and memory: O(bytes), entries at most kMaxListLineBytes each.
bool ParseList(std::string_view text, std::vector<ListEntry>* out, std::string* error);
// "" for an acceptable path; else why not (no line number): over kMaxListLineBytes, a NUL byte,
// another control character (C0, DEL).
std::string EntryProblem(std::string_view entry);
// At most `max_bytes` of `s` with control bytes written as \xNN and "..." when cut.
std::string PrintableExcerpt(std::string_view s, size_t max_bytes);

}  // namespace silkgen
