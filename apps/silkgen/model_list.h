// SPDX-License-Identifier: MIT
// silkgen --list-models: the models a user can pass to --model by name (silk_models_list), one line
// each, so an imported model can be found again without remembering its folder.
#pragma once
#include <string>

namespace silkgen {

// The table of silk_models_list's JSON: name, architecture, size, decoders and KV caches (defaults
// marked), folder; then the models folder. Throws silk_cpp::Error when libsilk cannot list.
std::string ModelListText(const std::string& catalog_json);

}  // namespace silkgen
