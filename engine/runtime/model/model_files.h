// SPDX-License-Identifier: MIT
// Keeps a model folder's reads inside the folder: every file it names (model.json's file
// names and the ONNX graphs' external-data locations) must resolve, symlinks followed, to a
// file under the folder, so a downloaded model cannot make libsilk read other files.
#pragma once
#include <string>
#include <vector>

#include "core/status.h"
#include "runtime/model/model_config.h"

namespace silk {

// `location` (as `named_by` names it; `what` says which kind of name it is) must be relative,
// without a ".." component, and resolve to an existing file inside `dir`. The error (kParseError,
// or kIoError for a missing file) names `named_by` and the location.
Status CheckInsideModelFolder(const std::string& dir, const std::string& location, const std::string& named_by,
                              const std::string& what);

// The files model.json names (encoder, the decoder to load, external_data) and every
// external-data location inside `onnx_files` (plain names in dir) stay inside dir.
Status CheckModelFolderFiles(const std::string& dir, const ModelConfig& config,
                             const std::vector<std::string>& onnx_files);

}  // namespace silk
