// SPDX-License-Identifier: MIT
// What every ai.silk onnxruntime op needs around its kernel, written against the plain C API and
// the OrtApi the op was registered with (libsilk's own onnxruntime or Python's): reading tensors,
// naming shapes in messages, onnxruntime's pool as a parallel-for, the op table's fixed entries.
#pragma once
#include <onnxruntime_c_api.h>

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace silk {

#define SILK_ORT_TRY(expr)                   \
  do {                                       \
    if (OrtStatus* st_ = (expr)) return st_; \
  } while (0)

// An op table entry that remembers the API it was made for, its name and input/output counts.
struct SilkCustomOp : OrtCustomOp {
  const OrtApi* api = nullptr;
  const char* name = "";
  size_t inputs = 0, outputs = 0;
};

struct OrtTensorView {
  void* data = nullptr;
  std::vector<int64_t> dims;
  ONNXTensorElementDataType type = ONNX_TENSOR_ELEMENT_DATA_TYPE_UNDEFINED;
};

// Shape, element type and data of input `index` (a missing input is an error naming `what`).
OrtStatus* ReadInput(const OrtApi* api, OrtKernelContext* ctx, size_t index, OrtTensorView* t);
OrtStatus* DescribeValue(const OrtApi* api, OrtValue* value, OrtTensorView* t);

// What every op's kernel keeps: the API, its op and node names for messages.
struct OpKernelBase {
  const OrtApi* api = nullptr;
  const char* op = "";
  std::string node;
  // An INVALID_ARGUMENT status "<op> '<node>': <what>".
  OrtStatus* Fail(const std::string& what) const;
};

// Output `index` as a float32 tensor of `dims`, and its data.
OrtStatus* FloatOutput(const OrtApi* api, OrtKernelContext* ctx, size_t index, const std::vector<int64_t>& dims,
                       float** data);

// "[1, 2, 3]"
std::string DimsText(const std::vector<int64_t>& dims);
int64_t ElementCount(const std::vector<int64_t>& dims);

// The node's name ("" when onnxruntime has none).
std::string NodeName(const OrtApi* api, const OrtKernelInfo* info);

// A ParallelForFn context for onnxruntime's intra-op pool of this kernel call (falls back to a
// plain loop when onnxruntime has no pool to offer).
struct OrtPool {
  const OrtApi* api;
  const OrtKernelContext* ctx;
};
void OrtPoolFor(void* pool, void (*work)(void*, size_t), void* state, size_t count);

// Zeroes the table and sets the entries every ai.silk op shares (API version, CPU, all inputs
// and outputs required, start version 1) and those its fields answer (name, input and output
// counts); the op sets its input/output types and, with SetKernel, its kernel.
void FillOpTable(SilkCustomOp* op, const OrtApi* api, const char* name, size_t inputs, size_t outputs);

// A new kernel of type K (an OpKernelBase) for node `info`: the op's API and name, the node's name.
template <typename K>
std::unique_ptr<K> NewKernel(const OrtCustomOp* op, const OrtApi* api, const OrtKernelInfo* info) {
  auto k = std::make_unique<K>();
  k->api = static_cast<const SilkCustomOp*>(op)->api;
  k->op = static_cast<const SilkCustomOp*>(op)->name;
  k->node = NodeName(api, info);
  return k;
}

// The table's kernel entries: `create` makes a K, `compute` runs it, and it is deleted as a K.
template <typename K>
void SetKernel(SilkCustomOp* op, decltype(OrtCustomOp::CreateKernelV2) create,
               decltype(OrtCustomOp::KernelComputeV2) compute) {
  op->KernelDestroy = [](void* kernel) { delete static_cast<K*>(kernel); };
  op->CreateKernelV2 = create;
  op->KernelComputeV2 = compute;
}

}  // namespace silk
