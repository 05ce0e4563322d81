// SPDX-License-Identifier: MIT
// Where tests find the shared spec/corpus data.
#include "support/test_paths.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>

namespace silk::testing {
// The C++ side of the one shared-folder rule: the run-time variable wins over CMake's finding.
std::string SharedDir() {
  if (const char* e = std::getenv("SILK_SHARED_DIR"); e && *e) return e;
  return SILK_SHARED_DIR;
}
std::string SharedPath(const std::string& rel) { return SharedDir() + "/" + rel; }
std::string SourcePath(const std::string& rel) { return std::string(SILK_SOURCE_DIR) + "/" + rel; }

namespace {
// Without the shared material the golden and corpus tests would fail one by one (and those that
// index the ids they read, crash); this stops every test executable before its first test with one
// message naming the folder (gtest runs no test after a global set-up's fatal failure).
class SharedDataPresent : public ::testing::Environment {
 public:
  void SetUp() override {
    ASSERT_TRUE(std::ifstream(SharedPath("spec/golden/cube.tokens.txt")).good())
        << "no shared material in " << SharedDir()
        << " (spec/golden/cube.tokens.txt unreadable): set SILK_SHARED_DIR to the folder holding spec/ and corpus/";
  }
};
[[maybe_unused]] ::testing::Environment* const kSharedDataPresent =
    ::testing::AddGlobalTestEnvironment(new SharedDataPresent);
}  // namespace
}  // namespace silk::testing
