// SPDX-License-Identifier: MIT
// Finding the bundled model when --model is not given: next to the installed binary
// (<bin>/../share/silk/models/default; the pip wheel: silk_mesh/bin/../model; the Windows zip:
// models/default beside silkgen.exe), then the source tree's models/default (build tree only).
#pragma once
#include <string>
#include <vector>

namespace silkgen {

// Folders tried, in order (only existing ones are returned by DefaultModelDir).
std::vector<std::string> DefaultModelCandidates();
// The first candidate holding a model.json, or "".
std::string DefaultModelDir();

}  // namespace silkgen
