// SPDX-License-Identifier: MIT
// The --batch list parser (batch_list.h): one pass over the text, string views until an entry is kept.
#include "batch_list.h"

#include <cstdio>

namespace silkgen {
namespace {

bool IsBlank(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }

std::string_view Trim(std::string_view s) {
  while (!s.empty() && IsBlank(s.front())) s.remove_prefix(1);
  while (!s.empty() && IsBlank(s.back())) s.remove_suffix(1);
  return s;
}

}  // namespace

std::string PrintableExcerpt(std::string_view s, size_t max_bytes) {
  std::string out;
  for (size_t i = 0; i < s.size(); ++i) {
    const unsigned char c = static_cast<unsigned char>(s[i]);
    if (out.size() + 4 > max_bytes) return out + "...";
    if (c < 0x20 || c == 0x7f) {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\x%02x", c);
      out += buf;
    } else {
      out += static_cast<char>(c);
    }
  }
  return out;
}

std::string EntryProblem(std::string_view entry) {
  if (entry.size() > kMaxListLineBytes)
    return "is " + std::to_string(entry.size()) + " bytes, longer than a path may be (" +
           std::to_string(kMaxListLineBytes) + ")";
  for (size_t i = 0; i < entry.size(); ++i) {
    const unsigned char c = static_cast<unsigned char>(entry[i]);
    if (c == 0) return "holds a NUL byte at byte " + std::to_string(i + 1);
    if (c < 0x20 || c == 0x7f) {
      char buf[8];
      std::snprintf(buf, sizeof buf, "0x%02x", c);
      return std::string("holds a control character (") + buf + ") at byte " + std::to_string(i + 1);
    }
  }
  return "";
}

bool ParseList(std::string_view text, std::vector<ListEntry>* out, std::string* error) {
  size_t pos = 0, line_no = 0;
  while (pos < text.size()) {
    size_t nl = text.find('\n', pos);
    if (nl == std::string_view::npos) nl = text.size();
    ++line_no;
    const std::string_view entry = Trim(text.substr(pos, nl - pos));
    pos = nl + 1;
    if (entry.empty() || entry[0] == '#') continue;
    if (out->size() >= kMaxListEntries) {
      *error = "more than " + std::to_string(kMaxListEntries) + " entries (split the list)";
      return false;
    }
    ListEntry e;
    e.line = line_no;
    e.problem = EntryProblem(entry);
    if (e.problem.empty()) {
      e.entry = std::string(entry);
    } else {
      e.problem = "list line " + std::to_string(line_no) + " " + e.problem + " (not a usable path)";
      e.entry = PrintableExcerpt(entry, 200);
    }
    out->push_back(std::move(e));
  }
  return true;
}

}  // namespace silkgen
