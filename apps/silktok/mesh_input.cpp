// SPDX-License-Identifier: MIT
// Reading + encoding one mesh file for silktok (silk_mesh_load, silk_mesh_encode).
#include "mesh_input.h"

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

}  // namespace silktok
