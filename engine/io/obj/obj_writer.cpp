// SPDX-License-Identifier: MIT
// OBJ formatting with std::to_chars (shortest round-trip doubles) and atomic file output.
#include "io/obj/obj_writer.h"

#include <charconv>
#include <cmath>

#include "io/files/atomic_file.h"
#include "io/mesh_validation.h"

namespace silk {

StatusOr<std::string> FormatObj(const IoMesh& mesh, const ObjWriteOptions& opts) {
  SILK_RETURN_IF_ERROR(ValidateOutputMesh(mesh));
  std::string out;
  out.reserve(mesh.positions.size() * 32 + mesh.triangles.size() * 24);
  if (!opts.header_comment.empty()) {
    size_t start = 0;
    while (start <= opts.header_comment.size()) {
      size_t nl = opts.header_comment.find('\n', start);
      if (nl == std::string::npos) nl = opts.header_comment.size();
      out += "# " + opts.header_comment.substr(start, nl - start) + "\n";
      start = nl + 1;
    }
  }
  char buf[64];
  for (size_t i = 0; i < mesh.positions.size(); ++i) {
    out += 'v';
    for (double c : mesh.positions[i]) {
      out += ' ';
      std::to_chars_result r;
      if (opts.integer_coordinates) {
        if (c != std::trunc(c) || std::fabs(c) > 9.0e15)
          return InvalidArgument("vertex " + std::to_string(i) + ": coordinate is not an integer");
        r = std::to_chars(buf, buf + sizeof(buf), static_cast<long long>(c));
      } else {
        r = std::to_chars(buf, buf + sizeof(buf), c);
      }
      out.append(buf, r.ptr);
    }
    out += '\n';
  }
  for (const auto& t : mesh.triangles) {
    out += 'f';
    for (int32_t v : t) {
      out += ' ';
      auto r = std::to_chars(buf, buf + sizeof(buf), static_cast<int64_t>(v) + 1);
      out.append(buf, r.ptr);
    }
    out += '\n';
  }
  return out;
}

Status WriteObjFile(const std::string& path, const IoMesh& mesh, const ObjWriteOptions& opts) {
  StatusOr<std::string> text = FormatObj(mesh, opts);
  if (!text.ok()) return text.status().WithContext(path + ": ");
  return WriteFileAtomically(path, *text);
}

}  // namespace silk
