// SPDX-License-Identifier: MIT
// glTF reading: pre-checks, tinygltf load with restricted file callbacks, scene walk,
// primitive extraction. No exception thrown by tinygltf or nlohmann leaves this file.
#include "io/gltf/gltf_reader.h"

#include <new>

#include <tiny_gltf.h>

#include "io/files/file_bytes.h"
#include "io/files/file_system.h"
#include "io/gltf/glb_container.h"
#include "io/gltf/gltf_json_checks.h"
#include "io/gltf/gltf_primitives.h"
#include "io/gltf/gltf_scene_walk.h"
#include "io/read_error.h"

namespace silk {

namespace {

struct FsContext {
  bool from_memory = false;
  uint64_t max_bytes = 0;
};

bool FileExistsCb(const std::string& path, void* user) {
  const auto* ctx = static_cast<const FsContext*>(user);
  if (ctx->from_memory) return false;
  return IsRegularFile(path);
}

std::string ExpandFilePathCb(const std::string& path, void*) { return path; }

bool ReadWholeFileCb(std::vector<unsigned char>* out, std::string* err, const std::string& path, void* user) {
  const auto* ctx = static_cast<const FsContext*>(user);
  if (ctx->from_memory) {
    if (err) *err += "external file '" + path + "' cannot be loaded (mesh read from memory)\n";
    return false;
  }
  if (!IsRegularFile(path)) {
    if (err) *err += "external file '" + path + "' not found\n";
    return false;
  }
  StatusOr<std::string> bytes = ReadFileBytes(path, ctx->max_bytes);
  if (!bytes.ok()) {
    if (err && bytes.status().code() == StatusCode::kLimitExceeded)
      *err += "external file '" + path + "' is larger than the size limit\n";
    else if (err)
      *err += "cannot open external file '" + path + "'\n";
    return false;
  }
  out->assign(bytes->begin(), bytes->end());
  return true;
}

bool WriteWholeFileCb(std::string* err, const std::string&, const std::vector<unsigned char>&, void*) {
  if (err) *err += "writing is disabled\n";
  return false;
}

// Images are not needed for geometry: accept them without decoding.
bool NoImageLoader(tinygltf::Image*, const int, std::string*, std::string*, int, int, const unsigned char*, int,
                   void*) {
  return true;
}

std::string FirstLine(const std::string& s) {
  std::string l = s.substr(0, s.find('\n'));
  return l.size() > 300 ? l.substr(0, 300) + "..." : l;
}

}  // namespace

StatusOr<IoMesh> ReadGltf(std::string_view data, bool binary, const std::string& name, const std::string& base_dir,
                          bool from_memory, const ReadOptions& opts) {
  std::string_view json = data;
  if (binary) {
    SILK_ASSIGN_OR_RETURN(GlbChunks chunks, ParseGlbContainer(data, name));
    json = chunks.json;
  } else if (data.size() >= 4 && data.substr(0, 4) == "glTF") {
    return ParseErrorIn(name, "binary GLB content in a .gltf file");
  }
  if (data.size() > 0xFFFFFFFFull) return LimitErrorIn(name, "glTF file larger than 4 GiB");
  SILK_RETURN_IF_ERROR(CheckGltfJsonText(json, name));
  SILK_RETURN_IF_ERROR(CheckGltfExternalBuffers(json, name, base_dir, from_memory));

  IoMesh mesh;
  try {
    tinygltf::Model model;
    tinygltf::TinyGLTF loader;
    FsContext ctx{from_memory, opts.max_file_bytes};
    tinygltf::FsCallbacks fs{&FileExistsCb, &ExpandFilePathCb, &ReadWholeFileCb, &WriteWholeFileCb, &ctx};
    loader.SetFsCallbacks(fs);
    loader.SetImageLoader(&NoImageLoader, nullptr);
    std::string err, warn;
    bool ok;
    if (binary) {
      ok = loader.LoadBinaryFromMemory(&model, &err, &warn, reinterpret_cast<const unsigned char*>(data.data()),
                                       static_cast<unsigned int>(data.size()), base_dir);
    } else {
      ok = loader.LoadASCIIFromString(&model, &err, &warn, data.data(), static_cast<unsigned int>(data.size()),
                                      base_dir);
    }
    if (!ok) return ParseErrorIn(name, "glTF: " + (err.empty() ? std::string("tinygltf failed") : FirstLine(err)));

    SILK_ASSIGN_OR_RETURN(std::vector<GltfMeshInstance> instances, CollectGltfMeshInstances(model, name));
    for (const GltfMeshInstance& inst : instances)
      SILK_RETURN_IF_ERROR(AppendGltfMeshInstance(model, inst, name, opts, &mesh));
  } catch (const std::bad_alloc&) {
    return LimitErrorIn(name, "out of memory while reading glTF");
  } catch (const std::exception& e) {
    return ParseErrorIn(name, std::string("glTF: ") + e.what());
  } catch (...) {
    return ParseErrorIn(name, "glTF: unknown failure");
  }
  if (mesh.triangles.empty()) return ParseErrorIn(name, "no faces (no triangle primitives in the scene)");
  return mesh;
}

}  // namespace silk
