// SPDX-License-Identifier: MIT
// PLY binary_little_endian formatting (explicit byte order) and atomic file output.
#include "io/ply/ply_writer.h"

#include <cstring>

#include "io/files/atomic_file.h"
#include "io/mesh_validation.h"

namespace silk {

namespace {
template <typename T>
void PutLE(std::string* out, T v) {
  unsigned char b[sizeof(T)];
  std::memcpy(b, &v, sizeof(T));
#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_BIG_ENDIAN__
  for (size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(b[i], b[sizeof(T) - 1 - i]);
#endif
  out->append(reinterpret_cast<const char*>(b), sizeof(T));
}
}  // namespace

StatusOr<std::string> FormatPlyBinary(const IoMesh& mesh, const PlyWriteOptions& opts) {
  SILK_RETURN_IF_ERROR(ValidateOutputMesh(mesh));
  const char* type = opts.float32_coordinates ? "float" : "double";
  std::string out = "ply\nformat binary_little_endian 1.0\ncomment written by silk\n";
  out += "element vertex " + std::to_string(mesh.positions.size()) + "\n";
  for (const char* axis : {"x", "y", "z"}) out += std::string("property ") + type + " " + axis + "\n";
  out += "element face " + std::to_string(mesh.triangles.size()) + "\n";
  out += "property list uchar int vertex_indices\nend_header\n";
  out.reserve(out.size() + mesh.positions.size() * 24 + mesh.triangles.size() * 13);
  for (const auto& p : mesh.positions)
    for (double c : p) {
      if (opts.float32_coordinates)
        PutLE(&out, static_cast<float>(c));
      else
        PutLE(&out, c);
    }
  for (const auto& t : mesh.triangles) {
    out.push_back(3);
    for (int32_t v : t) PutLE(&out, v);
  }
  return out;
}

Status WritePlyFile(const std::string& path, const IoMesh& mesh, const PlyWriteOptions& opts) {
  StatusOr<std::string> bytes = FormatPlyBinary(mesh, opts);
  if (!bytes.ok()) return bytes.status().WithContext(path + ": ");
  return WriteFileAtomically(path, *bytes);
}

}  // namespace silk
