// SPDX-License-Identifier: MIT
// Shared plumbing of the C API: handle structs, the per-thread error slot, and Guard(),
// which turns Status and any C++ exception into a silk_status so nothing crosses the ABI.
#pragma once
#include <array>
#include <cstddef>
#include <cstring>
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

// silk_encode_params (NULL: defaults) for silk_mesh_encode and silk_mesh_roundtrip: struct_size,
// flags and normalize_bound, failures prefixed with `function`.
silk_status CheckEncodeParams(const char* function, const silk_encode_params* params);
// The one encode path of silk_mesh_encode and silk_mesh_roundtrip: `params` (NULL: defaults;
// CheckEncodeParams has passed them) read, the mesh normalised when they ask, then encoded.
StatusOr<EncodeResult> EncodeWithParams(const silk_mesh& mesh, const silk_encode_params* params);

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

// The one size-query rule of every copy function (silk.h, docs/c_api.md): *out_count (if given)
// = needed; (NULL, 0) is the size query (SILK_OK, nothing copied); NULL with a capacity is an
// invalid argument; a capacity below `needed` is SILK_ERR_BUFFER_TOO_SMALL. Returns true when the
// copy should go ahead; otherwise *answer is the call's status.
bool BeginCopy(const char* function, const void* out, size_t capacity, size_t needed, size_t* out_count,
               silk_status* answer);

// The one struct_size rule (docs/c_api.md "Struct growth"): `given` must be a size this library
// has shipped for `type`: sizeof, `older` (the size libsilk 1.0 shipped, 0: none) or `older13`
// (the size libsilk 1.3-1.4 shipped, 0: none); otherwise SILK_ERR_INVALID_ARGUMENT naming the
// struct, the size given and the sizes expected, and `how` (the way to initialise it).
silk_status CheckStructSize(const char* function, const char* type, uint32_t given, size_t expected,
                            const std::string& how, size_t older = 0, size_t older13 = 0);
// The size libsilk 1.0 shipped for a struct that has grown since (0: it has not grown). Its
// fields are only appended, so the 1.0 size is the offset of the first field added after 1.0.
template <typename T>
inline constexpr size_t kSize10 = 0;
template <>
inline constexpr size_t kSize10<silk_model_params> = offsetof(silk_model_params, kv_precision);
template <>
inline constexpr size_t kSize10<silk_model_info> = offsetof(silk_model_info, kv_precision);
template <>
inline constexpr size_t kSize10<silk_generate_params> = offsetof(silk_generate_params, face_guidance);
template <>
inline constexpr size_t kSize10<silk_generate_stats> = offsetof(silk_generate_stats, face_guided_tokens);
// The size libsilk 1.3-1.4 shipped for a struct that has grown since (0: it has not grown since
// 1.3): the offset of the first field 1.5 appended.
template <typename T>
inline constexpr size_t kSize13 = 0;
template <>
inline constexpr size_t kSize13<silk_generate_params> = offsetof(silk_generate_params, rows);
template <>
inline constexpr size_t kSize13<silk_generate_stats> = offsetof(silk_generate_stats, rows);

// A params struct (NULL: fine, the defaults apply) and a struct the library fills (NULL: fine
// where optional; the caller checks required ones).
template <typename T>
silk_status CheckParamsSize(const char* function, const char* type, const T* p, const char* defaults) {
  return p ? CheckStructSize(function, type, p->struct_size, sizeof(T), std::string("initialise it with ") + defaults,
                             kSize10<T>, kSize13<T>)
           : SILK_OK;
}
template <typename T>
silk_status CheckOutSize(const char* function, const char* type, const T* p) {
  return p ? CheckStructSize(function, type, p->struct_size, sizeof(T),
                             std::string("set struct_size = sizeof(") + type + ") before the call", kSize10<T>,
                             kSize13<T>)
           : SILK_OK;
}
// The caller's params over the defaults: only the caller's struct_size bytes are read.
template <typename T>
T ReadParams(const T* p, T defaults) {
  if (p) std::memcpy(&defaults, p, p->struct_size < sizeof(T) ? p->struct_size : sizeof(T));
  defaults.struct_size = static_cast<uint32_t>(sizeof(T));
  return defaults;
}
// `value` into the caller's out struct: only the caller's struct_size bytes are written.
template <typename T>
void StoreOut(T* out, T value) {
  const uint32_t size = out->struct_size;
  value.struct_size = size;
  std::memcpy(out, &value, size < sizeof(T) ? size : sizeof(T));
}
// A fresh value of an out struct (zeroed, struct_size set), for StoreOut.
template <typename T>
T Blank() {
  T t;
  std::memset(&t, 0, sizeof(t));
  t.struct_size = static_cast<uint32_t>(sizeof(T));
  return t;
}

#define SILK_CAPI_TRY(expr) \
  if (silk_status silk_try_ = (expr); silk_try_ != SILK_OK) return silk_try_
#define SILK_CAPI_REQUIRE(cond, what) \
  if (!(cond)) return ::silk::capi::SetError(SILK_ERR_INVALID_ARGUMENT, what)
// A field check (CheckFlag, CheckEnum, ...) of `function`'s params: on failure, its message
// prefixed with the function's name.
#define SILK_CAPI_CHECK(function, check)                       \
  if (::silk::Status silk_check_ = (check); !silk_check_.ok()) \
  return ::silk::capi::SetError(silk_check_.WithContext(function ": "))

}  // namespace silk::capi
