// Reading a mesh file and normalising it (spec §2.1) for the tokenizer, with errors that
// name the file.
#pragma once
#include <string>

#include "core/status.h"
#include "io/raw_mesh.h"
#include "tokenizer/tokenizer.h"

namespace silktok {

silk::StatusOr<silk::RawMesh> LoadNormalized(const std::string& path);
silk::StatusOr<silk::EncodeResult> LoadAndEncode(const std::string& path, const silk::EncodeOptions& options);
// "silktok: <message>" on stderr.
void ReportError(const silk::Status& s);

}  // namespace silktok
