// One Env per process (onnxruntime's logging/telemetry root); sessions get their own
// intra-op thread pools sized by the caller.
#include "runtime/ort_support.h"

namespace silk {

Ort::Env& OrtEnvironment() {
  static Ort::Env env(ORT_LOGGING_LEVEL_WARNING, "silk");
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
