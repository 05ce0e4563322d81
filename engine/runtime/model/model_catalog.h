// SPDX-License-Identifier: MIT
// The models a user can pick by name (the bundled one and each folder of the user's models folder),
// described from their model.json and file sizes without loading them: what `silkgen --list-models`,
// silk_mesh and the Blender add-on's model drop-down show (silk_models_list).
#pragma once
#include <string>

namespace silk {

// At most this many folders of the models folder are described (the rest are counted).
inline constexpr int kMaxListedModels = 1000;

// JSON: {"models_dir": PATH or null, "models_dir_error": "..." (only when there is none), "models": [
//   {"name", "dir", "bundled", "arch", "config", "parameters" (d_model/layers/heads), "bytes",
//    "decoders": ["fp32","int8",...], "default_decoder", "kv_precisions": ["fp32","fp16",...],
//    "default_kv_precision"} or {"name", "dir", "bundled", "bytes", "error": "..."} for a folder
//   that is not a usable model], "not_listed": N}. The bundled model (name "default") comes first,
// then the models folder's subfolders in name order.
std::string ModelCatalogJson();

}  // namespace silk
