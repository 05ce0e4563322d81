// Reading + encoding one mesh file for silktok, and its error messages (the kind names are
// the library's own, silk_status_name).
#include "mesh_input.h"

#include <cstdio>

namespace silktok {

silk_cpp::Mesh LoadMesh(const std::string& path) {
  silk_load_params p = silk_load_default_params();
  p.point_clouds = 0;  // the tokenizer reads every file as a mesh
  return silk_cpp::Mesh::Load(path, p);
}

silk_cpp::Tokens LoadAndEncode(const std::string& path, const silk_encode_params& params, silk_encode_stats* stats) {
  const silk_cpp::Mesh mesh = LoadMesh(path);
  try {
    return mesh.Encode(params, stats);
  } catch (const silk_cpp::Error& e) {
    throw WithContext(e, path + ": ");
  }
}

silk_cpp::Error WithContext(const silk_cpp::Error& e, const std::string& prefix) {
  return AppError(e.status(), prefix + e.message());
}

silk_cpp::Error AppError(silk_status status, const std::string& message) {
  return silk_cpp::Error(status, std::string(silk_status_name(status)) + ": " + message, message);
}

void ReportError(const silk_cpp::Error& e) { std::fprintf(stderr, "silktok: %s\n", e.what()); }

}  // namespace silktok
