// SPDX-License-Identifier: MIT
// Linux builds with SILK_ORT_RUNTIME_LOAD (the pip wheel; see ort_dll_load.h): dlopen by full path
// (or one already loaded, RTLD_NOLOAD) + dlsym("OrtGetApiBase").
#if defined(SILK_ORT_RUNTIME_LOAD) && !defined(_WIN32)
#include <dlfcn.h>
#include <onnxruntime_c_api.h>

#include <climits>
#include <cstdlib>
#include <string>

#include "io/files/module_folder.h"
#include "runtime/model/ort_runtime_load.h"

#ifndef SILK_ORT_SONAME
#error "SILK_ORT_SONAME (onnxruntime's soname, e.g. libonnxruntime.so.1) is set by cmake/SilkOnnxRuntime.cmake"
#endif
#ifndef SILK_ORT_RELATIVE_PATH
#error "SILK_ORT_RELATIVE_PATH (onnxruntime relative to libsilk's folder) is set by cmake/SilkOnnxRuntime.cmake"
#endif

namespace silk {

namespace {

// folder + "/" + rel, with rel's leading "../" applied to folder (so messages show a plain path).
std::string JoinRelative(std::string folder, std::string rel) {
  while (rel.rfind("../", 0) == 0 && folder.rfind('/') != std::string::npos && folder.rfind('/') > 0) {
    folder.resize(folder.rfind('/'));
    rel.erase(0, 3);
  }
  return folder + "/" + rel;
}

// The file a loaded library came from (for messages), found through one of its symbols.
std::string FileOf(void* symbol, const std::string& fallback) {
  Dl_info info{};
  return dladdr(symbol, &info) && info.dli_fname ? std::string(info.dli_fname) : fallback;
}

Status InitFrom(void* lib, const std::string& fallback_name) {
  using GetApiBase = const OrtApiBase* (*)();
  auto get_base = reinterpret_cast<GetApiBase>(dlsym(lib, "OrtGetApiBase"));
  if (!get_base) return IoError(fallback_name + ": not an onnxruntime library (no OrtGetApiBase)");
  const std::string name = FileOf(reinterpret_cast<void*>(get_base), fallback_name);
  return InitOrtApi(get_base(), name);
}

}  // namespace

Status LoadOnnxRuntimeForPlatform() {
  // Already in the process (RTLD_NOLOAD never searches a path): silk_mesh's preload.
  if (void* lib = dlopen(SILK_ORT_SONAME, RTLD_NOW | RTLD_LOCAL | RTLD_NOLOAD)) {
    Status s = InitFrom(lib, SILK_ORT_SONAME);
    if (!s.ok()) dlclose(lib);  // our reference only: the preloader keeps its own
    return s;
  }
  const std::string own = ModuleFolder();
  const std::string path = JoinRelative(own.empty() ? "." : own, SILK_ORT_RELATIVE_PATH);
  void* lib = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (!lib) {
    const char* err = dlerror();
    std::string why = err ? err : "unknown reason";
    if (why.rfind(path + ": ", 0) == 0) why.erase(0, path.size() + 2);  // dlerror repeats the path
    return IoError(path +
                   ": cannot load onnxruntime (needed for generation; the onnxruntime package "
                   "belongs beside silk_mesh): " +
                   why);
  }
  Status s = InitFrom(lib, path);
  if (!s.ok()) dlclose(lib);  // unusable: let a later try load a replacement
  return s;
}

}  // namespace silk
#endif  // SILK_ORT_RUNTIME_LOAD && !_WIN32
