// SPDX-License-Identifier: MIT
// Model loading: model.json, then the ONNX sessions, whose inputs/outputs are checked against
// docs/model_contract.md (names, element types, ranks, and every fixed dimension).
#include "runtime/model/model_impl.h"

#include <array>

#include "io/files/file_system.h"
#include "io/files/native_path.h"
#include "kernels/cpu/cpu_info.h"
#include "kernels/cpu/float16.h"
#include "runtime/kv_cache.h"
#include "runtime/model/model_files.h"
#ifdef SILK_ORT_RUNTIME_LOAD
#include "runtime/model/ort_dll_load.h"
#endif
#include "runtime/sampling/generation_ranges.h"

namespace silk {

namespace {

struct IoSpec {
  std::string name;
  ONNXTensorElementDataType type;
  std::vector<int64_t> dims;  // -1: dynamic (not checked)
};

std::string DimsText(const std::vector<int64_t>& d) {
  std::string s = "[";
  for (size_t i = 0; i < d.size(); ++i) s += (i ? ", " : "") + (d[i] < 0 ? std::string("?") : std::to_string(d[i]));
  return s + "]";
}

std::string TypeName(ONNXTensorElementDataType t) {
  switch (t) {
    case ONNX_TENSOR_ELEMENT_DATA_TYPE_FLOAT:
      return "float32";
    case ONNX_TENSOR_ELEMENT_DATA_TYPE_FLOAT16:
      return "float16";
    case ONNX_TENSOR_ELEMENT_DATA_TYPE_INT64:
      return "int64";
    case ONNX_TENSOR_ELEMENT_DATA_TYPE_INT32:
      return "int32";
    case ONNX_TENSOR_ELEMENT_DATA_TYPE_INT8:
      return "int8";
    default:
      return "ONNX type " + std::to_string(static_cast<int>(t));
  }
}

// Checks one side (inputs or outputs) of a session against the contract.
Status CheckIo(Ort::Session& s, bool inputs, const std::vector<IoSpec>& want, const std::string& file) {
  const size_t n = inputs ? s.GetInputCount() : s.GetOutputCount();
  const char* side = inputs ? "inputs" : "outputs";
  Ort::AllocatorWithDefaultOptions alloc;
  if (n != want.size())
    return Status(StatusCode::kUnsupported, file + ": has " + std::to_string(n) + " " + side + ", the contract has " +
                                                std::to_string(want.size()));
  for (size_t i = 0; i < n; ++i) {
    const std::string name =
        inputs ? s.GetInputNameAllocated(i, alloc).get() : s.GetOutputNameAllocated(i, alloc).get();
    const IoSpec* spec = nullptr;
    for (const IoSpec& w : want)
      if (name == w.name) spec = &w;
    if (!spec) return Status(StatusCode::kUnsupported, file + ": unexpected " + side + " name '" + name + "'");
    Ort::TypeInfo ti = inputs ? s.GetInputTypeInfo(i) : s.GetOutputTypeInfo(i);
    auto t = ti.GetTensorTypeAndShapeInfo();
    if (t.GetElementType() != spec->type)
      return Status(StatusCode::kUnsupported, file + ": '" + name + "' has element type " +
                                                  TypeName(t.GetElementType()) + ", the contract needs " +
                                                  TypeName(spec->type));
    std::vector<int64_t> dims = t.GetShape();
    bool ok = dims.size() == spec->dims.size();
    for (size_t k = 0; ok && k < dims.size(); ++k) ok = spec->dims[k] < 0 || dims[k] < 0 || dims[k] == spec->dims[k];
    if (!ok)
      return Status(StatusCode::kUnsupported, file + ": '" + name + "' has shape " + DimsText(dims) +
                                                  ", model.json implies " + DimsText(spec->dims));
  }
  return Status::Ok();
}

// The element type of the decoder's cross_key_0 when it is float16 (the silk form of the cache
// variants), else float32; CheckIo then holds every cross_* input to it, naming any other.
ONNXTensorElementDataType CrossType(Ort::Session& s) {
  Ort::AllocatorWithDefaultOptions alloc;
  for (size_t i = 0; i < s.GetInputCount(); ++i)
    if (std::string(s.GetInputNameAllocated(i, alloc).get()) == "cross_key_0" &&
        s.GetInputTypeInfo(i).GetTensorTypeAndShapeInfo().GetElementType() == ONNX_TENSOR_ELEMENT_DATA_TYPE_FLOAT16)
      return ONNX_TENSOR_ELEMENT_DATA_TYPE_FLOAT16;
  return ONNX_TENSOR_ELEMENT_DATA_TYPE_FLOAT;
}

// Whether the decoder takes contract v4's per-row inputs (new_positions names them).
bool HasRowsInputs(Ort::Session& s) {
  Ort::AllocatorWithDefaultOptions alloc;
  for (size_t i = 0; i < s.GetInputCount(); ++i)
    if (std::string(s.GetInputNameAllocated(i, alloc).get()) == "new_positions") return true;
  return false;
}

// The float32 cross_kv as a float16 tensor of the same shape (rounded to nearest even).
Ort::Value HalfCopy(Ort::Value& cross) {
  const std::vector<int64_t> shape = cross.GetTensorTypeAndShapeInfo().GetShape();
  Ort::AllocatorWithDefaultOptions alloc;
  Ort::Value half = Ort::Value::CreateTensor(alloc, shape.data(), shape.size(), ONNX_TENSOR_ELEMENT_DATA_TYPE_FLOAT16);
  const float* from = cross.GetTensorData<float>();
  uint16_t* to = half.GetTensorMutableData<uint16_t>();
  const size_t n = cross.GetTensorTypeAndShapeInfo().GetElementCount();
  for (size_t i = 0; i < n; ++i) to[i] = FloatToHalf(from[i]);
  return half;
}

// The encoder's fixed point count from its input shape, which must match dims.n_points.
StatusOr<int64_t> EncoderPoints(Ort::Session& s, int32_t n_points, const std::string& file) {
  Ort::TypeInfo ti = s.GetInputTypeInfo(0);
  const std::vector<int64_t> dims = ti.GetTensorTypeAndShapeInfo().GetShape();
  const int64_t n = dims.size() == 3 ? dims[1] : -1;
  if (n >= 0 && n != n_points)
    return Unsupported(file + ": the encoder takes " + std::to_string(n) + " points, model.json dims.n_points is " +
                       std::to_string(n_points));
  return n < 0 ? int64_t{-1} : n;
}

std::string Upper(const std::string& s) {
  std::string u;
  for (char ch : s) u += static_cast<char>(ch >= 'a' && ch <= 'z' ? ch - 'a' + 'A' : ch);
  return u;
}

// The decoder file of a weight precision and KV precision, or an error naming both and the folder.
StatusOr<std::string> ChooseDecoderFile(const std::string& dir, const ModelConfig& config, DecoderPrecision p,
                                        KvPrecision kv) {
  const std::string name = DecoderPrecisionName(p);
  const std::string key = p == DecoderPrecision::kFp32 ? "decoder" : "decoder_" + name;
  if (config.DecoderFile(p).empty())
    return Unsupported(dir + "/model.json: no " + Upper(name) + " decoder (files." + key + ") in this model");
  if (config.DecoderFile(p, kv).empty())
    return Unsupported(dir + ": no " + KvPrecisionName(kv) + " KV cache variant of the " + Upper(name) +
                       " decoder in this model folder (files." + KvFilesKey(kv) + "." + key +
                       " in model.json; add one with `silk-export " + KvExportCommand(kv) + "`)");
  return config.DecoderFile(p, kv);
}

}  // namespace

std::vector<std::string> DecoderInputNames(int64_t n_layers, bool rows) {
  std::vector<std::string> names = {"input_ids", "positions", "seqlens_k", "total_sequence_length"};
  if (rows) names.insert(names.end(), {"new_positions", "cross_source"});
  for (const char* group : {"past_", "cross_"})
    for (int64_t l = 0; l < n_layers; ++l)
      for (const char* kv : {"key_", "value_"}) names.push_back(group + std::string(kv) + std::to_string(l));
  return names;
}

std::vector<std::string> DecoderOutputNames(int64_t n_layers) {
  std::vector<std::string> names = {"logits"};
  for (int64_t l = 0; l < n_layers; ++l)
    for (const char* kv : {"key_", "value_"}) names.push_back("present_" + std::string(kv) + std::to_string(l));
  return names;
}

Model::Model(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
Model::~Model() = default;
const ModelConfig& Model::config() const { return impl_->config; }
int Model::threads() const { return impl_->threads; }
DecoderPrecision Model::precision() const { return impl_->precision; }
KvPrecision Model::kv_precision() const { return impl_->kv_precision; }
int64_t Model::encoder_points() const { return impl_->encoder_points; }

StatusOr<std::unique_ptr<Model>> Model::Load(const std::string& dir, const ModelLoadOptions& options) {
  if (!IsDirectory(dir)) return IoError(dir + ": model folder not found");
  SILK_ASSIGN_OR_RETURN(ModelConfig config, LoadModelConfig(dir));
  SILK_RETURN_IF_ERROR(CheckSetting(ranges::Threads(), options.threads));
#ifdef SILK_ORT_RUNTIME_LOAD
  SILK_RETURN_IF_ERROR(LoadOnnxRuntimeLibrary());  // before any Ort object; names the library file
#endif
  auto impl = std::make_unique<Impl>();
  impl->precision = options.decoder.value_or(config.default_decoder);
  impl->kv_precision = options.kv.value_or(config.DefaultKv(impl->precision));
  SILK_ASSIGN_OR_RETURN(const std::string decoder_file,
                        ChooseDecoderFile(dir, config, impl->precision, impl->kv_precision));
  const std::string enc_path = dir + "/" + config.encoder_file, dec_path = dir + "/" + decoder_file;
  for (const std::string& p : {enc_path, dec_path})
    if (!IsRegularFile(p)) return IoError(p + ": missing (named in model.json)");
  SILK_RETURN_IF_ERROR(CheckModelFolderFiles(dir, config, {config.encoder_file, decoder_file}));

  const ModelDims& d = config.dims;
  const int64_t V = config.model_vocab_size;
  const std::vector<int64_t> cross = {d.n_layers, 2, d.n_heads, d.n_latents, d.head_dim};
  constexpr auto kF = ONNX_TENSOR_ELEMENT_DATA_TYPE_FLOAT;
  constexpr auto kI = ONNX_TENSOR_ELEMENT_DATA_TYPE_INT64;
  constexpr auto kI32 = ONNX_TENSOR_ELEMENT_DATA_TYPE_INT32;
  const KvShape kv_shape = KvShapeOf(config.dims, impl->kv_precision);
  const ONNXTensorElementDataType kKv = KvOnnxType(impl->kv_precision);
  std::vector<IoSpec> dec_in = {{"input_ids", kI, {1, -1}},
                                {"positions", kI, {1, -1}},
                                {"seqlens_k", kI32, {1}},
                                {"total_sequence_length", kI32, {}}};
  std::vector<IoSpec> dec_out = {{"logits", kF, {1, -1, V}}};
  for (const std::string& name : DecoderInputNames(d.n_layers))
    if (name.rfind("past_", 0) == 0) dec_in.push_back({name, kKv, {1, d.n_heads, -1, kv_shape.row_dims()}});
  for (const std::string& name : DecoderInputNames(d.n_layers))
    if (name.rfind("cross_", 0) == 0) dec_in.push_back({name, kF, {1, d.n_heads, d.n_latents, d.head_dim}});
  for (const std::string& name : DecoderOutputNames(d.n_layers))
    if (name != "logits") dec_out.push_back({name, kKv, {1, d.n_heads, -1, kv_shape.row_dims()}});
  Status s = OrtGuard("loading " + dir, [&]() -> Status {
    Ort::Env& env = OrtEnvironment(options.threads, options.allow_spinning);
    impl->threads = SharedPoolThreads();
    Ort::SessionOptions so = MakeOrtSessionOptions();
    // ORTCHAR_T is the native path character (wchar_t on Windows): NativePath's UTF-16 there.
    impl->encoder = std::make_unique<Ort::Session>(env, NativePath(enc_path).c_str(), so);
    impl->decoder = std::make_unique<Ort::Session>(env, NativePath(dec_path).c_str(), so);
    impl->cross_type = CrossType(*impl->decoder);
    impl->rows_contract = HasRowsInputs(*impl->decoder);
    impl->rows_together = RowsTogether(impl->rows_contract, impl->precision);
    if (impl->rows_contract)  // one row: R = S = 1
      dec_in.insert(dec_in.begin() + 4, {{"new_positions", kI32, {1}}, {"cross_source", kI32, {1}}});
    for (IoSpec& spec : dec_in)
      if (spec.name.rfind("cross_", 0) == 0 && spec.name != "cross_source") spec.type = impl->cross_type;
    SILK_RETURN_IF_ERROR(CheckIo(*impl->encoder, true, {{"points", kF, {1, -1, 6}}}, enc_path));
    SILK_ASSIGN_OR_RETURN(impl->encoder_points, EncoderPoints(*impl->encoder, config.dims.n_points, enc_path));
    SILK_RETURN_IF_ERROR(CheckIo(*impl->encoder, false, {{"cross_kv", kF, cross}}, enc_path));
    SILK_RETURN_IF_ERROR(CheckIo(*impl->decoder, true, dec_in, dec_path));
    SILK_RETURN_IF_ERROR(CheckIo(*impl->decoder, false, dec_out, dec_path));
    return Status::Ok();
  });
  SILK_RETURN_IF_ERROR(s);
  impl->config = std::move(config);
  return std::unique_ptr<Model>(new Model(std::move(impl)));
}

StatusOr<Ort::Value> RunEncoder(const Model::Impl& model, const float* points, int64_t n_points,
                                const Ort::RunOptions& run_options) {
  if (n_points <= 0) return InvalidArgument("encoder: no input points");
  if (model.encoder_points >= 0 && n_points != model.encoder_points)
    return InvalidArgument("encoder: got " + std::to_string(n_points) + " points, the model's encoder takes exactly " +
                           std::to_string(model.encoder_points));
  Ort::Value out{nullptr};
  Status s = OrtGuard("encoder", [&]() -> Status {
    const std::array<int64_t, 3> shape = {1, n_points, 6};
    Ort::Value in = Ort::Value::CreateTensor<float>(model.cpu_memory, const_cast<float*>(points),
                                                    static_cast<size_t>(n_points * 6), shape.data(), shape.size());
    const char* in_names[] = {"points"};
    const char* out_names[] = {"cross_kv"};
    auto outs = model.encoder->Run(run_options, in_names, &in, 1, out_names, 1);
    const ModelDims& d = model.config.dims;
    auto shape_out = outs[0].GetTensorTypeAndShapeInfo().GetShape();
    const std::vector<int64_t> want = {d.n_layers, 2, d.n_heads, d.n_latents, d.head_dim};
    if (shape_out != want)
      return InternalError("encoder: cross_kv has shape " + DimsText(shape_out) + ", expected " + DimsText(want));
    out = model.cross_type == ONNX_TENSOR_ELEMENT_DATA_TYPE_FLOAT16 ? HalfCopy(outs[0]) : std::move(outs[0]);
    return Status::Ok();
  });
  SILK_RETURN_IF_ERROR(s);
  return StatusOr<Ort::Value>(std::move(out));
}

StatusOr<Ort::Value> EncodeInput(const Model::Impl& model, const std::vector<float>& points,
                                 const Ort::RunOptions& run_options, const CancelCheck& cancel) {
  if (CancelRequested(cancel)) return Status(StatusCode::kCancelled, "generation cancelled");
  auto encoded = RunEncoder(model, points.data(), static_cast<int64_t>(points.size() / 6), run_options);
  if (!encoded.ok() && CancelRequested(cancel)) return CancelledStatus("the encoder run");
  return encoded;
}

bool RowsTogether(bool rows_contract, DecoderPrecision precision) {
  return rows_contract && precision != DecoderPrecision::kInt8;
}

}  // namespace silk
