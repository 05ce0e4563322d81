// Windows (see ort_dll_load.h): LoadLibraryExW + GetProcAddress("OrtGetApiBase").
#if defined(_WIN32) && defined(SILK_ORT_RUNTIME_LOAD)
#include "runtime/model/ort_dll_load.h"

#include <onnxruntime_c_api.h>

#include <string>

#include "core/windows_text.h"
#include "runtime/model/ort_runtime_load.h"

namespace silk {

namespace {

// The folder of the module holding this code: libsilk.dll, or the program when linked statically.
std::wstring OwnFolder() {
  HMODULE self = nullptr;
  GetModuleHandleExW(GET_MODULE_HANDLE_EX_FLAG_FROM_ADDRESS | GET_MODULE_HANDLE_EX_FLAG_UNCHANGED_REFCOUNT,
                     reinterpret_cast<LPCWSTR>(&OwnFolder), &self);
  std::wstring p(32768, L'\0');
  const DWORD n = GetModuleFileNameW(self, p.data(), static_cast<DWORD>(p.size()));
  p.resize(n);
  const size_t slash = p.find_last_of(L"\\/");
  return slash == std::wstring::npos ? L"." : p.substr(0, slash);
}

}  // namespace

Status LoadOnnxRuntimeForPlatform() {
  const std::wstring path = OwnFolder() + L"\\onnxruntime.dll";
  const std::string name = Utf8FromWide(path);
  HMODULE dll = LoadLibraryExW(path.c_str(), nullptr, LOAD_WITH_ALTERED_SEARCH_PATH);
  if (!dll)
    return IoError(name + ": cannot load onnxruntime (needed for generation; it belongs next to libsilk.dll): " +
                   WindowsErrorText(GetLastError()));
  using GetApiBase = const OrtApiBase*(ORT_API_CALL*)();
  auto get_base = reinterpret_cast<GetApiBase>(reinterpret_cast<void*>(GetProcAddress(dll, "OrtGetApiBase")));
  Status s = get_base ? InitOrtApi(get_base(), name)
                      : IoError(name + ": not an onnxruntime library (no OrtGetApiBase)");
  if (!s.ok()) FreeLibrary(dll);  // unusable: let a later try load a replacement
  return s;
}

}  // namespace silk
#endif  // _WIN32
