// One Env per process (onnxruntime's logging/telemetry root); sessions get their own
// intra-op thread pools sized by the caller.
#include "runtime/ort_support.h"

#include <mutex>
#include <string>

namespace silk {

namespace {
std::mutex g_sink_mu;
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

Ort::Env& OrtEnvironment() {
  static Ort::Env env(ORT_LOGGING_LEVEL_WARNING, "silk", ForwardOrtLog, nullptr);
  return env;
}

Ort::SessionOptions MakeOrtSessionOptions(int threads, bool allow_spinning) {
  Ort::SessionOptions so;
  so.SetIntraOpNumThreads(threads);
  so.SetInterOpNumThreads(1);
  so.SetExecutionMode(ExecutionMode::ORT_SEQUENTIAL);
  so.SetGraphOptimizationLevel(GraphOptimizationLevel::ORT_ENABLE_ALL);
  so.AddConfigEntry("session.intra_op.allow_spinning", allow_spinning ? "1" : "0");
  return so;
}

}  // namespace silk
