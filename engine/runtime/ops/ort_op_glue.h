// What every ai.silk onnxruntime op needs around its kernel, written against the plain C API and
// the OrtApi the op was registered with (libsilk's own onnxruntime or Python's): reading tensors,
// naming shapes in messages, onnxruntime's pool as a parallel-for, the op table's fixed entries.
#pragma once
#include <onnxruntime_c_api.h>

#include <cstdint>
#include <string>
#include <vector>

namespace silk {

#define SILK_ORT_TRY(expr)                   \
  do {                                       \
    if (OrtStatus* st_ = (expr)) return st_; \
  } while (0)

// An op table entry that remembers the API it was made for.
struct SilkCustomOp : OrtCustomOp {
  const OrtApi* api = nullptr;
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
// and outputs required, start version 1); the op sets its name, types, kernel and compute.
void FillCommonOpEntries(SilkCustomOp* op, const OrtApi* api);

}  // namespace silk
