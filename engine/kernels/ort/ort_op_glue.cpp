// SPDX-License-Identifier: MIT
// Shared onnxruntime custom-op plumbing for the ai.silk ops (see ort_op_glue.h).
#include "kernels/ort/ort_op_glue.h"

#include <cstring>

namespace silk {

OrtStatus* DescribeValue(const OrtApi* api, OrtValue* value, OrtTensorView* t) {
  OrtTensorTypeAndShapeInfo* info = nullptr;
  SILK_ORT_TRY(api->GetTensorTypeAndShape(value, &info));
  size_t rank = 0;
  OrtStatus* st = api->GetDimensionsCount(info, &rank);
  if (!st) {
    t->dims.assign(rank, 0);
    st = api->GetDimensions(info, t->dims.data(), rank);
  }
  if (!st) st = api->GetTensorElementType(info, &t->type);
  api->ReleaseTensorTypeAndShapeInfo(info);
  if (!st) st = api->GetTensorMutableData(value, &t->data);
  return st;
}

OrtStatus* ReadInput(const OrtApi* api, OrtKernelContext* ctx, size_t index, OrtTensorView* t) {
  const OrtValue* v = nullptr;
  SILK_ORT_TRY(api->KernelContext_GetInput(ctx, index, &v));
  if (!v) return api->CreateStatus(ORT_INVALID_ARGUMENT, ("input " + std::to_string(index) + " is missing").c_str());
  return DescribeValue(api, const_cast<OrtValue*>(v), t);
}

OrtStatus* OpKernelBase::Fail(const std::string& what) const {
  return api->CreateStatus(ORT_INVALID_ARGUMENT, (std::string(op) + " '" + node + "': " + what).c_str());
}

OrtStatus* FloatOutput(const OrtApi* api, OrtKernelContext* ctx, size_t index, const std::vector<int64_t>& dims,
                       float** data) {
  OrtValue* out = nullptr;
  SILK_ORT_TRY(api->KernelContext_GetOutput(ctx, index, dims.data(), dims.size(), &out));
  return api->GetTensorMutableData(out, reinterpret_cast<void**>(data));
}

std::string DimsText(const std::vector<int64_t>& d) {
  std::string s = "[";
  for (size_t i = 0; i < d.size(); ++i) s += (i ? ", " : "") + std::to_string(d[i]);
  return s + "]";
}

int64_t ElementCount(const std::vector<int64_t>& dims) {
  int64_t n = 1;
  for (int64_t d : dims) n *= d;
  return n;
}

std::string NodeName(const OrtApi* api, const OrtKernelInfo* info) {
  size_t size = 0;
  if (OrtStatus* st = api->KernelInfo_GetNodeName(info, nullptr, &size)) {
    api->ReleaseStatus(st);
    return "";
  }
  if (size == 0) return "";
  std::string name(size, '\0');
  if (OrtStatus* st = api->KernelInfo_GetNodeName(info, name.data(), &size)) {
    api->ReleaseStatus(st);
    return "";
  }
  return name.c_str();
}

void OrtPoolFor(void* context, void (*work)(void*, size_t), void* state, size_t count) {
  const OrtPool* p = static_cast<const OrtPool*>(context);
  if (OrtStatus* st = p->api->KernelContext_ParallelFor(p->ctx, work, count, 0, state)) {
    p->api->ReleaseStatus(st);  // no pool: the same work on this thread
    for (size_t i = 0; i < count; ++i) work(state, i);
  }
}

void FillOpTable(SilkCustomOp* op, const OrtApi* api, const char* name, size_t inputs, size_t outputs) {
  std::memset(static_cast<OrtCustomOp*>(op), 0, sizeof(OrtCustomOp));
  op->api = api;
  op->name = name;
  op->inputs = inputs;
  op->outputs = outputs;
  op->version = ORT_API_VERSION;
  op->GetName = [](const OrtCustomOp* self) { return static_cast<const SilkCustomOp*>(self)->name; };
  op->GetInputTypeCount = [](const OrtCustomOp* self) { return static_cast<const SilkCustomOp*>(self)->inputs; };
  op->GetOutputTypeCount = [](const OrtCustomOp* self) { return static_cast<const SilkCustomOp*>(self)->outputs; };
  op->GetExecutionProviderType = [](const OrtCustomOp*) -> const char* { return nullptr; };
  op->GetInputCharacteristic = [](const OrtCustomOp*, size_t) { return INPUT_OUTPUT_REQUIRED; };
  op->GetOutputCharacteristic = [](const OrtCustomOp*, size_t) { return INPUT_OUTPUT_REQUIRED; };
  op->GetInputMemoryType = [](const OrtCustomOp*, size_t) { return OrtMemTypeDefault; };
  op->GetVariadicInputMinArity = [](const OrtCustomOp*) { return 1; };
  op->GetVariadicInputHomogeneity = [](const OrtCustomOp*) { return 1; };
  op->GetVariadicOutputMinArity = [](const OrtCustomOp*) { return 1; };
  op->GetVariadicOutputHomogeneity = [](const OrtCustomOp*) { return 1; };
  op->GetStartVersion = [](const OrtCustomOp*) { return 1; };
  op->GetEndVersion = [](const OrtCustomOp*) { return 1 << 30; };
}

}  // namespace silk
