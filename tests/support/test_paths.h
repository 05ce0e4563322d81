// SPDX-License-Identifier: MIT
// Where tests find the shared spec/corpus data: $SILK_SHARED_DIR at run time, else the folder CMake
// found by the one shared-folder rule (cmake/SilkSharedDir.cmake), compiled in.
#pragma once
#include <string>

namespace silk::testing {
std::string SharedDir();                         // .../shared
std::string SharedPath(const std::string& rel);  // SharedDir() + "/" + rel
std::string SourcePath(const std::string& rel);  // repo root + "/" + rel
}  // namespace silk::testing
