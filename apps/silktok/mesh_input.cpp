// Reading + normalising + encoding one mesh file for silktok.
#include "mesh_input.h"

#include <cstdio>

#include "io/mesh_reader.h"
#include "mesh/normalize.h"

namespace silktok {

silk::StatusOr<silk::RawMesh> LoadNormalized(const std::string& path) {
  auto raw = silk::ReadMeshFile(path);
  if (!raw.ok()) return raw.status();
  auto norm = silk::NormalizeMesh(*raw);
  if (!norm.ok()) return norm.status().WithContext(path + ": ");
  return norm;
}

silk::StatusOr<silk::EncodeResult> LoadAndEncode(const std::string& path, const silk::EncodeOptions& options) {
  auto norm = LoadNormalized(path);
  if (!norm.ok()) return norm.status();
  auto enc = silk::EncodeMesh(*norm, options);
  if (!enc.ok()) return enc.status().WithContext(path + ": ");
  return enc;
}

void ReportError(const silk::Status& s) { std::fprintf(stderr, "silktok: %s\n", s.ToString().c_str()); }

}  // namespace silktok
