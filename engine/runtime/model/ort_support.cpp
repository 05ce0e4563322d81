// SPDX-License-Identifier: MIT
// One Env per process (onnxruntime's logging/telemetry root) holding one intra-op thread pool
// that all sessions of all models share, so loading several models does not multiply threads.
#include "runtime/model/ort_support.h"

#include <algorithm>
#include <mutex>
#include <string>
#include <thread>

#include "kernels/silk_ops.h"
#include "kernels/cpu/cpu_info.h"
#include "runtime/sampling/generation_ranges.h"

namespace silk {

namespace {
std::mutex g_sink_mu;
int g_pool_threads = 0;
OrtLogSink g_sink = nullptr;
void* g_sink_user = nullptr;

void ForwardOrtLog(void*, OrtLoggingLevel severity, const char*, const char*, const char*, const char* message) {
  std::lock_guard<std::mutex> lock(g_sink_mu);
  if (g_sink) g_sink(static_cast<int>(severity), (std::string("onnxruntime: ") + message).c_str(), g_sink_user);
}
}  // namespace

void SetOrtLogSink(OrtLogSink sink, void* user_data) {
  std::lock_guard<std::mutex> lock(g_sink_mu);
  g_sink = sink;
  g_sink_user = user_data;
}

Ort::Env& OrtEnvironment(int threads, bool allow_spinning) {
  static Ort::Env env = [&] {
    g_pool_threads = std::clamp(threads > 0 ? threads : PhysicalCoreCount(), 1, static_cast<int>(ranges::Threads().hi));
    Ort::ThreadingOptions to;
    to.SetGlobalIntraOpNumThreads(g_pool_threads);
    to.SetGlobalInterOpNumThreads(1);
    to.SetGlobalSpinControl(allow_spinning ? 1 : 0);
    return Ort::Env(to, ForwardOrtLog, nullptr, ORT_LOGGING_LEVEL_WARNING, "silk");
  }();
  return env;
}

int SharedPoolThreads() { return g_pool_threads; }

Ort::SessionOptions MakeOrtSessionOptions() {
  Ort::SessionOptions so;
  so.DisablePerSessionThreads();
  so.SetExecutionMode(ExecutionMode::ORT_SEQUENTIAL);
  so.SetGraphOptimizationLevel(GraphOptimizationLevel::ORT_ENABLE_ALL);
  Ort::ThrowOnError(AddSilkOps(so, &Ort::GetApi()));  // ai.silk ops (fp16-cache decoders)
  return so;
}

}  // namespace silk
