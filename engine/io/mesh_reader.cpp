// SPDX-License-Identifier: MIT
// Format dispatch for files and memory buffers; gzip unwrapping; content sniffing.
#include "io/mesh_reader.h"

#include <new>
#include <string_view>

#include "io/files/file_bytes.h"
#include "io/gltf/gltf_reader.h"
#include "io/files/gzip_inflate.h"
#include "io/obj/obj_reader.h"
#include "io/off/off_reader.h"
#include "io/pmd/pmd_reader.h"
#include "io/ply/ply_reader.h"
#include "io/read_error.h"
#include "io/stl/stl_reader.h"
#include "io/xyz/xyz_reader.h"

namespace silk {

namespace {

StatusOr<IoMesh> Dispatch(std::string_view bytes, MeshFormat fmt, const std::string& name, const std::string& base_dir,
                          bool from_memory, const ReadOptions& opts) {
  try {
    switch (fmt) {
      case MeshFormat::kObj:
        return ReadObj(bytes, name, opts);
      case MeshFormat::kPly:
        return ReadPly(bytes, name, opts);
      case MeshFormat::kStl:
        return ReadStl(bytes, name, opts);
      case MeshFormat::kOff:
        return ReadOff(bytes, name, opts);
      case MeshFormat::kGltf:
        return ReadGltf(bytes, false, name, base_dir, from_memory, opts);
      case MeshFormat::kGlb:
        return ReadGltf(bytes, true, name, base_dir, from_memory, opts);
      case MeshFormat::kPmd:
        return ReadPmd(bytes, name, opts);
      case MeshFormat::kXyz: {
        SILK_ASSIGN_OR_RETURN(IoPointCloud pc, ReadXyz(bytes, name, opts));
        return ParseErrorIn(
            name, "no faces (an XYZ file is a point cloud of " + std::to_string(pc.mesh.positions.size()) + " points)");
      }
    }
  } catch (const std::bad_alloc&) {
    return LimitErrorIn(name, "out of memory");
  } catch (const std::exception& e) {
    return InternalError(name + ": " + e.what());
  }
  return InternalError(name + ": unknown mesh format");
}

std::string DirName(const std::string& path) {
#ifdef _WIN32
  size_t slash = path.find_last_of("/\\");  // either separator (std::filesystem writes '\\')
#else
  size_t slash = path.find_last_of('/');
#endif
  if (slash == std::string::npos) return ".";
  if (slash == 0) return "/";
  return path.substr(0, slash);
}

}  // namespace

StatusOr<std::string> ReadInputFileBytes(const std::string& path, const ReadOptions& opts) {
  std::string bytes;
  { SILK_ASSIGN_OR_RETURN(bytes, ReadFileBytes(path, opts.max_file_bytes)); }
  if (HasGzipSuffix(path)) {
    SILK_ASSIGN_OR_RETURN(std::string inflated, GunzipBytes(bytes, path, InflatedLimit(opts, bytes.size())));
    bytes.swap(inflated);
  }
  return bytes;
}

StatusOr<IoMesh> ReadMeshFile(const std::string& path, const ReadOptions& opts) {
  SILK_ASSIGN_OR_RETURN(std::string bytes, ReadInputFileBytes(path, opts));
  const auto* data = reinterpret_cast<const uint8_t*>(bytes.data());
  std::optional<MeshFormat> fmt = MeshFormatFromPath(path);
  const std::optional<MeshFormat> sniffed = SniffMeshFormat(data, bytes.size());
  if (!fmt) {
    if (!sniffed)
      return Unsupported(path +
                         ": unknown mesh format (extension not one of .obj .ply .stl .off .gltf .glb .pmd .xyz .pts)");
    fmt = sniffed;
  }
  // A .gltf that is really a GLB container is read as GLB; a .glb without the magic is an
  // error from the GLB reader ("not a GLB file (no 'glTF' magic)").
  if (*fmt == MeshFormat::kGltf && sniffed == MeshFormat::kGlb) fmt = MeshFormat::kGlb;
  return Dispatch(bytes, *fmt, path, DirName(path), /*from_memory=*/false, opts);
}

StatusOr<IoMesh> ReadMeshFromMemory(const uint8_t* data, size_t size, MeshFormat fmt, const std::string& name,
                                    const ReadOptions& opts) {
  if (size > opts.max_file_bytes) return LimitErrorIn(name, "input larger than the size limit");
  // Copy so the text readers always see a terminated buffer of their own.
  std::string bytes = size ? std::string(reinterpret_cast<const char*>(data), size) : std::string();
  return Dispatch(bytes, fmt, name, std::string(), /*from_memory=*/true, opts);
}

}  // namespace silk
