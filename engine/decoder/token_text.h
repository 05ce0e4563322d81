// Token files (*.tokens.txt): one decimal id per line, as in spec/golden. Read/write for the
// grammar's tools and tests; errors name the file and line.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "core/status.h"

namespace silk {

StatusOr<std::vector<int32_t>> ReadTokenText(const std::string& path);
Status WriteTokenText(const std::string& path, const std::vector<int32_t>& ids);

}  // namespace silk
