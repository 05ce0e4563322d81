// Where tests find the shared spec/corpus data.
#include "support/test_paths.h"

#include <cstdlib>

namespace silk::testing {
std::string SharedDir() {
  if (const char* e = std::getenv("SILK_SHARED_DIR"); e && *e) return e;
  return SILK_SHARED_DIR;
}
std::string SharedPath(const std::string& rel) { return SharedDir() + "/" + rel; }
std::string SourcePath(const std::string& rel) { return std::string(SILK_SOURCE_DIR) + "/" + rel; }
}  // namespace silk::testing
