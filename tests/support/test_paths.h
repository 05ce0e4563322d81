// SPDX-License-Identifier: MIT
// Where tests find the shared spec/corpus data (../shared beside the repo, or $SILK_SHARED_DIR).
#pragma once
#include <string>

namespace silk::testing {
std::string SharedDir();                         // .../shared
std::string SharedPath(const std::string& rel);  // SharedDir() + "/" + rel
std::string SourcePath(const std::string& rel);  // repo root + "/" + rel
}  // namespace silk::testing
