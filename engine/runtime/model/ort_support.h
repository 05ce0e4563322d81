// SPDX-License-Identifier: MIT
// onnxruntime plumbing shared by the runtime: the process-wide Env, session options from our
// settings, and OrtGuard, which turns Ort::Exception (and any other) into a Status so no
// exception leaves the runtime layer.
#pragma once
#include <exception>
#include <new>
#include <string>

#include <onnxruntime_cxx_api.h>

#include "core/status.h"

namespace silk {

// The process's Env, created on first use with one global intra-op thread pool that every
// session shares (sessions are made with DisablePerSessionThreads). The first caller's thread
// count and spinning setting size the pool; later values are ignored (SharedPoolThreads says
// what the pool has).
Ort::Env& OrtEnvironment(int threads = 0, bool allow_spinning = true);
int SharedPoolThreads();

// onnxruntime's own log lines (warnings and errors; their text also reaches the caller inside
// the returned Status) go to this sink instead of stderr. Default: none, nothing is printed.
// `severity` is onnxruntime's OrtLoggingLevel. Process-wide, thread-safe.
using OrtLogSink = void (*)(int severity, const char* message, void* user_data);
void SetOrtLogSink(OrtLogSink sink, void* user_data);
// Session options for the shared pool (no per-session threads), with libsilk's ai.silk ops.
Ort::SessionOptions MakeOrtSessionOptions();

template <typename F>
Status OrtGuard(const std::string& what, F&& f) noexcept {
  try {
    return f();
  } catch (const Ort::Exception& e) {
    return Status(StatusCode::kInternal, what + ": onnxruntime: " + e.what());
  } catch (const std::bad_alloc&) {
    return Status(StatusCode::kLimitExceeded, what + ": out of memory");
  } catch (const std::exception& e) {
    return Status(StatusCode::kInternal, what + ": " + e.what());
  } catch (...) {
    return Status(StatusCode::kInternal, what + ": unknown exception");
  }
}

}  // namespace silk
