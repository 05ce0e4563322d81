// Shared plumbing of the C API: handle structs, the per-thread error slot, and Guard(),
// which turns Status and any C++ exception into a silk_status so nothing crosses the ABI.
#pragma once
#include <array>
#include <exception>
#include <memory>
#include <new>
#include <string>
#include <vector>

#include "core/status.h"
#include "core/value_text.h"
#include "io/io_mesh.h"
#include "mesh/point_preprocessing.h"
#include "silk/silk.h"
#include "tokenizer/tokenizer.h"

// The C API's mesh handle (docs/mesh_types.md): an IoMesh plus what the caller can ask for besides.
struct silk_mesh {
  silk::IoMesh mesh;
  std::vector<int32_t> triangle_component;
  std::vector<std::array<double, 3>> normals;  // point clouds: one per vertex, else empty
  std::string source;                          // the file it was loaded from (for messages), or ""
};

struct silk_tokens {
  std::vector<int32_t> ids;
};

struct silk_report {
  std::string json;
};

namespace silk::capi {

silk_status SetError(silk_status code, const std::string& message);
silk_status SetError(const Status& s);
silk_status Ok();
// Pre-processing parameters across the boundary (capi_preprocess.cpp).
silk_preprocess_params ToCPreprocess(const PreprocessingParams& p);
PreprocessingParams FromCPreprocess(const silk_preprocess_params& p);
void Log(silk_log_level level, const std::string& message);
// The one TokenizerDecodedMesh -> silk_mesh step (capi_mesh.cpp): `positions` (the decoded grid
// positions dequantised, left on the grid, or in the input frame) with the decoded faces and
// their parts (component per triangle).
std::unique_ptr<silk_mesh> MeshHandle(std::vector<std::array<double, 3>> positions,
                                      const TokenizerDecodedMesh& decoded);

// Field checks of the params structs (capi_params.cpp): Ok, or an InvalidArgument naming the
// field and the value given ("round_float16 2 takes 0 or 1").
using silk::ValueText;  // "-0.5", "nan", "inf" (core/value_text.h)
Status CheckFlag(const char* field, int32_t value);
Status CheckEnum(const char* field, int32_t value, int32_t lo, int32_t hi, const char* type);

template <typename F>
silk_status Guard(F&& f) noexcept {
  try {
    return f();
  } catch (const std::bad_alloc&) {
    return SetError(SILK_ERR_LIMIT, "out of memory");
  } catch (const std::exception& e) {
    return SetError(SILK_ERR_INTERNAL, std::string("internal error: ") + e.what());
  } catch (...) {
    return SetError(SILK_ERR_INTERNAL, "internal error: unknown exception");
  }
}

// (out, capacity) of a query-then-copy call needing `needed` elements: OK to copy, a size
// query answered, or too small. Returns SILK_OK only when the copy should go ahead.
silk_status CheckCopy(const char* function, const void* out, size_t capacity, size_t needed);

#define SILK_CAPI_REQUIRE(cond, what) \
  if (!(cond)) return ::silk::capi::SetError(SILK_ERR_INVALID_ARGUMENT, what)
// A field check (CheckFlag, CheckEnum, ...) of `function`'s params: on failure, its message
// prefixed with the function's name.
#define SILK_CAPI_CHECK(function, check)                                      \
  if (::silk::Status silk_check_ = (check); !silk_check_.ok())                \
  return ::silk::capi::SetError(silk_check_.WithContext(function ": "))

}  // namespace silk::capi
