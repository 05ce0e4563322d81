// Reading and writing one-id-per-line token files (see token_text.h).
#include "decoder/token_text.h"

#include <cerrno>
#include <climits>
#include <cstdlib>
#include <fstream>

namespace silk {

StatusOr<std::vector<int32_t>> ReadTokenText(const std::string& path) {
  std::ifstream in(path);
  if (!in) return IoError(path + ": cannot open");
  std::vector<int32_t> ids;
  std::string line;
  int64_t line_no = 0;
  while (std::getline(in, line)) {
    ++line_no;
    size_t a = line.find_first_not_of(" \t\r");
    if (a == std::string::npos || line[a] == '#') continue;
    size_t b = line.find_last_not_of(" \t\r");
    const std::string t = line.substr(a, b - a + 1);
    char* end = nullptr;
    errno = 0;
    const long long v = std::strtoll(t.c_str(), &end, 10);
    if (errno != 0 || end == t.c_str() || *end != '\0' || v < INT32_MIN || v > INT32_MAX)
      return ParseError(path + ":" + std::to_string(line_no) + ": not an integer token id: '" + t + "'");
    ids.push_back(static_cast<int32_t>(v));
    if (ids.size() > (size_t{1} << 24)) return LimitExceeded(path + ": more than 16M ids");
  }
  return ids;
}

Status WriteTokenText(const std::string& path, const std::vector<int32_t>& ids) {
  std::ofstream out(path);
  if (!out) return IoError(path + ": cannot write");
  for (int32_t id : ids) out << id << '\n';
  if (!out) return IoError(path + ": write failed");
  return Status::Ok();
}

}  // namespace silk
