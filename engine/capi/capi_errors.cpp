// SPDX-License-Identifier: MIT
// C API: per-thread error messages, status names, version, the log callback,
// vocabulary, and the two boundary rules every call shares: the size query of copies and the
// struct_size check.
#include <atomic>
#include <mutex>

#include "capi/capi_internal.h"
#include "tokenizer/vocabulary_layout.h"
#ifdef SILK_HAVE_RUNTIME
#include "runtime/model/ort_support.h"
#endif

namespace silk::capi {
namespace {
thread_local std::string g_last_error;
std::mutex g_log_mu;
silk_log_fn g_log_fn = nullptr;
void* g_log_user = nullptr;

silk_status CodeOf(StatusCode c) {
  switch (c) {
    case StatusCode::kOk:
      return SILK_OK;
    case StatusCode::kInvalidArgument:
      return SILK_ERR_INVALID_ARGUMENT;
    case StatusCode::kIoError:
      return SILK_ERR_IO;
    case StatusCode::kParseError:
      return SILK_ERR_PARSE;
    case StatusCode::kUnsupported:
      return SILK_ERR_UNSUPPORTED;
    case StatusCode::kRefused:
      return SILK_ERR_REFUSED;
    case StatusCode::kLimitExceeded:
      return SILK_ERR_LIMIT;
    case StatusCode::kCancelled:
      return SILK_ERR_CANCELLED;
    case StatusCode::kInternal:
      return SILK_ERR_INTERNAL;
  }
  return SILK_ERR_INTERNAL;
}

#ifdef SILK_HAVE_RUNTIME
// onnxruntime's log lines, forwarded to the user's callback (verbose/info/warning/error/fatal).
void ForwardOrt(int severity, const char* message, void*) {
  Log(severity >= ORT_LOGGING_LEVEL_ERROR     ? SILK_LOG_ERROR
      : severity == ORT_LOGGING_LEVEL_WARNING ? SILK_LOG_WARN
      : severity == ORT_LOGGING_LEVEL_INFO    ? SILK_LOG_INFO
                                              : SILK_LOG_DEBUG,
      message);
}
#endif
}  // namespace

silk_status SetError(silk_status code, const std::string& message) {
  g_last_error = message;
  if (code != SILK_OK) Log(SILK_LOG_ERROR, message);
  return code;
}
silk_status SetError(const Status& s) { return s.ok() ? Ok() : SetError(CodeOf(s.code()), s.message()); }
silk_status Ok() {
  g_last_error.clear();
  return SILK_OK;
}
bool BeginCopy(const char* function, const void* out, size_t capacity, size_t needed, size_t* out_count,
               silk_status* answer) {
  if (out_count) *out_count = needed;
  if (!out && capacity == 0) {
    *answer = Ok();  // the size query
    return false;
  }
  if (!out) {
    *answer = SetError(SILK_ERR_INVALID_ARGUMENT, std::string(function) + ": out is NULL with capacity " +
                                                      std::to_string(capacity) + " (a size query passes NULL, 0)");
    return false;
  }
  if (capacity < needed) {
    *answer = SetError(SILK_ERR_BUFFER_TOO_SMALL, std::string(function) + ": need " + std::to_string(needed) +
                                                      " elements, capacity is " + std::to_string(capacity));
    return false;
  }
  return true;
}

silk_status CheckStructSize(const char* function, const char* type, uint32_t given, size_t expected,
                            const std::string& how, size_t older, size_t older13) {
  // Every size this library has shipped for the type: today's, and libsilk 1.0's and 1.3's for a
  // struct that has grown since (docs/c_api.md "Struct growth").
  if (given == expected || (older != 0 && given == older) || (older13 != 0 && given == older13)) return SILK_OK;
  return SetError(SILK_ERR_INVALID_ARGUMENT,
                  std::string(function) + ": " + type + ".struct_size " + std::to_string(given) + " is not a size of " +
                      type + " this library knows (expected " + std::to_string(expected) +
                      (older ? ", or " + std::to_string(older) + " as libsilk 1.0 shipped it" : std::string()) +
                      (older13 ? ", or " + std::to_string(older13) + " as libsilk 1.3-1.4 shipped it" : std::string()) +
                      "): " + how);
}

void Log(silk_log_level level, const std::string& message) {
  std::lock_guard<std::mutex> lock(g_log_mu);
  if (g_log_fn) g_log_fn(level, message.c_str(), g_log_user);
}

}  // namespace silk::capi

extern "C" {

const char* silk_last_error(void) { return silk::capi::g_last_error.c_str(); }

const char* silk_status_name(silk_status s) {
  switch (s) {
    case SILK_OK:
      return "ok";
    case SILK_ERR_INVALID_ARGUMENT:
      return "invalid argument";
    case SILK_ERR_IO:
      return "I/O error";
    case SILK_ERR_PARSE:
      return "parse error";
    case SILK_ERR_UNSUPPORTED:
      return "unsupported";
    case SILK_ERR_REFUSED:
      return "refused";
    case SILK_ERR_LIMIT:
      return "limit exceeded";
    case SILK_ERR_CANCELLED:
      return "cancelled";
    case SILK_ERR_INTERNAL:
      return "internal error";
    case SILK_ERR_BUFFER_TOO_SMALL:
      return "buffer too small";
    case SILK_ERR_BUSY:
      return "generator busy";
  }
  return "unknown";
}

const char* silk_version(void) { return SILK_VERSION_STRING; }

void silk_log_set_callback(silk_log_fn fn, void* user_data) {
  {
    std::lock_guard<std::mutex> lock(silk::capi::g_log_mu);
    silk::capi::g_log_fn = fn;
    silk::capi::g_log_user = user_data;
  }
#ifdef SILK_HAVE_RUNTIME
  // Outside g_log_mu: the forwarder takes the sink's lock, then g_log_mu.
  silk::SetOrtLogSink(fn ? silk::capi::ForwardOrt : nullptr, nullptr);
#endif
}

silk_status silk_vocab_get_info(silk_vocab_info* out) {
  return silk::capi::Guard([&] {
    SILK_CAPI_REQUIRE(out, "silk_vocab_get_info: out is NULL");
    SILK_CAPI_TRY(silk::capi::CheckOutSize("silk_vocab_get_info", "silk_vocab_info", out));
    namespace v = silk::vocab;
    silk_vocab_info i = silk::capi::Blank<silk_vocab_info>();
    i.token_format_version = v::k_token_format_version;
    i.format_vocab_size = v::k_format_vocab_size;
    i.eos_id = v::k_eos_id;
    i.pad_id = v::k_pad_id;
    i.model_vocab_size = v::k_model_vocab_size;
    i.c_id = v::kCBegin;
    i.u_id = v::kUBegin;
    i.e_id = v::kEBegin;
    i.x_begin = v::kXBegin;
    i.x_end = v::kXEnd;
    i.s_begin = v::kSBegin;
    i.s_end = v::kSEnd;
    i.b_begin = v::kBBegin;
    i.b_end = v::kBEnd;
    i.k_begin = v::kKBegin;
    i.k_end = v::kKEnd;
    i.o_begin = v::kOBegin;
    i.o_end = v::kOEnd;
    i.quant_bins = v::k_quant_bins;
    i.layer_vertex_limit = v::k_layer_vertex_limit;
    i.layer_count_limit = v::k_layer_count_limit;
    i.max_faces = v::k_max_faces;
    i.max_seq_length = v::k_max_seq_length;
    silk::capi::StoreOut(out, i);
    return silk::capi::Ok();
  });
}

}  // extern "C"
