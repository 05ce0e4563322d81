// SPDX-License-Identifier: MIT
// Model::Impl: the onnxruntime sessions behind a Model, with input/output names checked
// against the contract at load time. Internal to the runtime layer.
#pragma once
#include <memory>
#include <string>
#include <vector>

#include "core/cancel_check.h"
#include "runtime/model/model.h"
#include "runtime/model/ort_support.h"

namespace silk {

struct Model::Impl {
  ModelConfig config;
  int threads = 1;
  DecoderPrecision precision = DecoderPrecision::kFp32;
  KvPrecision kv_precision = KvPrecision::kFp32;
  int64_t encoder_points = -1;  // fixed N of encoder.onnx, -1: dynamic
  // The decoder's cross_* inputs: float32, or float16 in the silk form of the cache variants
  // (RunEncoder then converts the encoder's float32 cross_kv once).
  ONNXTensorElementDataType cross_type = ONNX_TENSOR_ELEMENT_DATA_TYPE_FLOAT;
  // Decoder contract v4 (R rows per call): the decoder also takes new_positions and cross_source
  // (int32 [R]); DecoderRunner runs it with one row (R = S = 1).
  bool rows_contract = false;
  // Whether best of N decodes its candidates as rows (RowsTogether below).
  bool rows_together = false;
  std::unique_ptr<Ort::Session> encoder, decoder;
  Ort::MemoryInfo cpu_memory = Ort::MemoryInfo::CreateCpu(OrtArenaAllocator, OrtMemTypeDefault);
};

// Whether the loaded decoder runs many sequences in one call with each row's logits exactly those
// of the row alone, however its ids are cut into calls: a contract v4 decoder with the ai.silk
// kernels or onnxruntime's float32 MatMul (measured bit for bit at the tiny, bundled and release
// sizes). Not the INT8 decoder: onnxruntime's DynamicQuantizeLinear takes one activation scale for
// every row and position of a call, so rows would move each other's ids; it runs one row at a time.
bool RowsTogether(bool rows_contract, DecoderPrecision precision);

// The element type of the decoder's past_*/present_* tensors for a KV precision.
inline ONNXTensorElementDataType KvOnnxType(KvPrecision p) {
  return p == KvPrecision::kFp16   ? ONNX_TENSOR_ELEMENT_DATA_TYPE_FLOAT16
         : p == KvPrecision::kInt8 ? ONNX_TENSOR_ELEMENT_DATA_TYPE_INT8
                                   : ONNX_TENSOR_ELEMENT_DATA_TYPE_FLOAT;
}

// decoder.onnx's input and output names in contract order (docs/model_contract.md):
// input_ids, positions, seqlens_k, total_sequence_length, [new_positions, cross_source: contract v4
// `rows`,] past_{key,value}_l, cross_{key,value}_l; logits, present_{key,value}_l.
std::vector<std::string> DecoderInputNames(int64_t n_layers, bool rows = false);
std::vector<std::string> DecoderOutputNames(int64_t n_layers);

// Runs encoder.onnx on `n_points` rows of 6 floats (normalised xyz, unit normal); the result
// is the cross_kv tensor [L, 2, H, M, D] of the decoder's cross_type that every decoder call
// then reads unchanged.
// run_options: SetTerminate on it from another thread stops the run (an error status).
StatusOr<Ort::Value> RunEncoder(const Model::Impl& model, const float* points, int64_t n_points,
                                const Ort::RunOptions& run_options = Ort::RunOptions{nullptr});

// RunEncoder for a generation's input (rows of 6 floats): `cancel` is polled before the run, and a
// run stopped by SetTerminate on `run_options` while `cancel` says so is reported as cancelled.
StatusOr<Ort::Value> EncodeInput(const Model::Impl& model, const std::vector<float>& points,
                                 const Ort::RunOptions& run_options, const CancelCheck& cancel);

}  // namespace silk
