// Finding the bundled model when --model is not given: next to the installed binary
// (<bin>/../share/silk/models/default), then the source tree's models/default.
#pragma once
#include <string>
#include <vector>

namespace silkgen {

// Folders tried, in order (only existing ones are returned by DefaultModelDir).
std::vector<std::string> DefaultModelCandidates();
// The first candidate holding a model.json, or "".
std::string DefaultModelDir();

}  // namespace silkgen
