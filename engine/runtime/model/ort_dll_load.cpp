// SPDX-License-Identifier: MIT
// Windows (see ort_dll_load.h): LoadLibraryExW + GetProcAddress("OrtGetApiBase").
#if defined(_WIN32) && defined(SILK_ORT_RUNTIME_LOAD)
#include "runtime/model/ort_dll_load.h"

#include <onnxruntime_c_api.h>

#include <string>

#include "core/windows_text.h"
#include "io/files/module_folder.h"
#include "runtime/model/ort_runtime_load.h"

namespace silk {

Status LoadOnnxRuntimeForPlatform() {
  const std::string own = ModuleFolder();
  const std::wstring path = WidePath(own.empty() ? "." : own) + L"\\onnxruntime.dll";
  const std::string name = Utf8FromWide(path);
  HMODULE dll = LoadLibraryExW(path.c_str(), nullptr, LOAD_WITH_ALTERED_SEARCH_PATH);
  if (!dll)
    return IoError(name + ": cannot load onnxruntime (needed for generation; it belongs next to libsilk.dll): " +
                   WindowsErrorText(GetLastError()));
  using GetApiBase = const OrtApiBase*(ORT_API_CALL*)();
  auto get_base = reinterpret_cast<GetApiBase>(reinterpret_cast<void*>(GetProcAddress(dll, "OrtGetApiBase")));
  Status s =
      get_base ? InitOrtApi(get_base(), name) : IoError(name + ": not an onnxruntime library (no OrtGetApiBase)");
  if (!s.ok()) FreeLibrary(dll);  // unusable: let a later try load a replacement
  return s;
}

}  // namespace silk
#endif  // _WIN32
