// SPDX-License-Identifier: MIT
// Token files: one decimal id per line.
#include "io/tokens/token_text.h"

#include <charconv>
#include <algorithm>
#include <climits>

#include "io/files/file_bytes.h"

namespace silk {

StatusOr<std::vector<int32_t>> ParseTokenText(const std::string& text, const std::string& name) {
  std::vector<int32_t> ids;
  size_t line_no = 0, pos = 0;
  while (pos < text.size()) {
    size_t end = text.find('\n', pos);
    if (end == std::string::npos) end = text.size();
    ++line_no;
    size_t a = pos, b = end;
    while (a < b && (text[a] == ' ' || text[a] == '\t' || text[a] == '\r')) ++a;
    while (b > a && (text[b - 1] == ' ' || text[b - 1] == '\t' || text[b - 1] == '\r')) --b;
    if (a < b) {
      int64_t v = 0;
      auto r = std::from_chars(text.data() + a, text.data() + b, v);
      if (r.ec != std::errc() || r.ptr != text.data() + b || v < -1 || v > INT32_MAX)
        return ParseError(name + ":" + std::to_string(line_no) + ": not a token id: '" +
                          text.substr(a, std::min<size_t>(b - a, 40)) + "'");
      ids.push_back(static_cast<int32_t>(v));
    }
    pos = end + 1;
  }
  return ids;
}

StatusOr<std::vector<int32_t>> ReadTokenText(const std::string& path, size_t max_bytes) {
  SILK_ASSIGN_OR_RETURN(std::string text, ReadFileBytes(path, max_bytes));
  return ParseTokenText(text, path);
}

std::string FormatTokenText(const std::vector<int32_t>& ids) {
  std::string out;
  out.reserve(ids.size() * 5);
  char buf[16];
  for (int32_t id : ids) {
    auto r = std::to_chars(buf, buf + sizeof buf, id);
    out.append(buf, r.ptr);
    out.push_back('\n');
  }
  return out;
}

}  // namespace silk
