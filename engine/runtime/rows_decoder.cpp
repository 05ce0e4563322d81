// SPDX-License-Identifier: MIT
// Many rows per decoder.onnx call: the rows' chunks padded to the longest (PAD ids, position 0),
// per-row lengths, the cache tensors over all rows' blocks and present_* bound to the same memory.
#include "runtime/rows_decoder.h"

#include <algorithm>
#include <array>
#include <cstring>

namespace silk {

namespace {
int64_t CrossElementBytes(const Model::Impl& m) {
  return m.cross_type == ONNX_TENSOR_ELEMENT_DATA_TYPE_FLOAT16 ? 2 : 4;
}
int64_t CrossSliceBytes(const Model::Impl& m) {  // one layer's keys or values of one encoder output
  const ModelDims& d = m.config.dims;
  return d.n_heads * d.n_latents * d.head_dim * CrossElementBytes(m);
}
}  // namespace

RowsDecoder::RowsDecoder(const Model::Impl& model, RowsKvCache* cache, int64_t max_chunk)
    : model_(model),
      cache_(cache),
      max_chunk_(std::max<int64_t>(1, max_chunk)),
      vocab_(model.config.model_vocab_size),
      in_names_(DecoderInputNames(model.config.dims.n_layers, model.rows_contract)),
      out_names_(DecoderOutputNames(model.config.dims.n_layers)),
      row_logits_(static_cast<size_t>(cache->slots() * model.config.model_vocab_size)) {
  for (const std::string& s : in_names_) in_ptrs_.push_back(s.c_str());
  for (const std::string& s : out_names_) out_ptrs_.push_back(s.c_str());
}

void RowsDecoder::SetSources(int32_t count) {
  sources_ = std::max(count, 0);
  cross_.assign(static_cast<size_t>(2 * model_.config.dims.n_layers * sources_ * CrossSliceBytes(model_)), 0);
  views_ = ViewKey{};  // the cross views point into cross_
}

void RowsDecoder::SetSource(int32_t index, const void* cross_kv) {
  const int64_t slice = CrossSliceBytes(model_);
  const auto* from = static_cast<const unsigned char*>(cross_kv);
  for (int64_t lk = 0; lk < 2 * model_.config.dims.n_layers; ++lk)
    std::memcpy(cross_.data() + (lk * sources_ + index) * slice, from + lk * slice, static_cast<size_t>(slice));
}

Status RowsDecoder::CheckRows(const std::vector<RowFeed>& rows) const {
  if (rows.empty()) return InvalidArgument("decoder: no rows to feed");
  const KvShape& s = cache_->shape();
  const ModelDims& d = model_.config.dims;
  if (s.layers != d.n_layers || s.heads != d.n_heads || s.head_dim != d.head_dim || s.precision != model_.kv_precision)
    return InvalidArgument("decoder: the rows cache was not reserved for this model's shape");
  std::vector<bool> seen(static_cast<size_t>(cache_->slots()), false);
  for (const RowFeed& r : rows) {
    if (r.slot < 0 || r.slot >= cache_->slots() || seen[static_cast<size_t>(r.slot)])
      return InvalidArgument("decoder: row slot " + std::to_string(r.slot) + " is out of range or repeated");
    seen[static_cast<size_t>(r.slot)] = true;
    if (r.n <= 0 || !r.ids) return InvalidArgument("decoder: nothing to feed for row " + std::to_string(r.slot));
    if (r.source < 0 || r.source >= sources_)
      return InvalidArgument("decoder: row " + std::to_string(r.slot) + " attends to encoder output " +
                             std::to_string(r.source) + " of " + std::to_string(sources_));
    if (cache_->length(r.slot) + r.n > cache_->max_capacity())
      return LimitExceeded("decoder: " + std::to_string(cache_->length(r.slot) + r.n) +
                           " positions exceed the cache of " + std::to_string(cache_->max_capacity()));
  }
  return Status::Ok();
}

Status RowsDecoder::Feed(const std::vector<RowFeed>& rows) {
  SILK_RETURN_IF_ERROR(CheckRows(rows));
  std::vector<int64_t> done(rows.size(), 0);
  int64_t needed = 0;
  int32_t top = 0;
  for (const RowFeed& r : rows) top = std::max(top, r.slot + 1);
  for (int32_t s = 0; s < top; ++s) needed = std::max(needed, cache_->length(s) + 1);  // placeholders
  for (const RowFeed& r : rows) needed = std::max(needed, cache_->length(r.slot) + r.n);
  SILK_RETURN_IF_ERROR(cache_->Ensure(needed));
  for (bool left = true; left;) {
    left = false;
    std::vector<Chunk> chunks(static_cast<size_t>(model_.rows_contract ? top : 1));
    for (size_t i = 0; i < rows.size(); ++i) {
      const RowFeed& r = rows[i];
      if (done[i] == r.n) continue;
      Chunk c{r.ids + done[i], std::min(max_chunk_, r.n - done[i]), r.source, false};
      c.last = done[i] + c.n == r.n && r.keep_logits;
      done[i] += c.n;
      if (!model_.rows_contract) {  // batch 1: this row alone, all its chunks in turn
        chunks[0] = c;
        SILK_RETURN_IF_ERROR(Call(r.slot, chunks));
        left = left || done[i] < r.n;
        continue;
      }
      chunks[static_cast<size_t>(r.slot)] = c;
      left = left || done[i] < r.n;
    }
    if (model_.rows_contract) SILK_RETURN_IF_ERROR(Call(0, chunks));
  }
  return Status::Ok();
}

Status RowsDecoder::Call(int32_t first, const std::vector<Chunk>& chunks) {
  int64_t T = 1;
  for (const Chunk& c : chunks) T = std::max(T, c.n);
  const int64_t R = static_cast<int64_t>(chunks.size());
  Stage(first, chunks, T);
  return OrtGuard("decoder", [&]() -> Status {
    ViewKey key{cache_->block(0, 0), cache_->capacity(), R, first, model_.rows_contract ? -1 : chunks[0].source};
    if (!(key == views_)) MakeViews(key);
    BindCallInputs(R, T);
    const std::array<int64_t, 3> logit_shape = {R, T, vocab_};
    out_values_[0] = Ort::Value::CreateTensor<float>(model_.cpu_memory, logits_.data(),
                                                     static_cast<size_t>(R * T * vocab_), logit_shape.data(), 3);
    model_.decoder->Run(Ort::RunOptions{nullptr}, in_ptrs_.data(), in_values_.data(), in_values_.size(),
                        out_ptrs_.data(), out_values_.data(), out_values_.size());
    ++calls_;
    positions_computed_ += R * T;
    KeepLogits(first, chunks, T);
    for (size_t r = 0; r < chunks.size(); ++r)
      if (chunks[r].n > 0) cache_->Extend(first + static_cast<int32_t>(r), chunks[r].n);
    return Status::Ok();
  });
}

// Row r's ids in columns 0..n-1 at positions P_r on, PAD and position 0 after; a placeholder row
// takes one id at its next position (written, not counted: its next real id overwrites it).
void RowsDecoder::Stage(int32_t first, const std::vector<Chunk>& chunks, int64_t T) {
  const size_t R = chunks.size();
  ids_.assign(R * T, model_.config.pad_id);
  positions_.assign(R * T, 0);
  seqlens_.resize(R);
  news_.resize(R);
  source_of_.resize(R);
  total_ = 0;
  for (size_t r = 0; r < R; ++r) {
    const Chunk& c = chunks[r];
    const int64_t P = cache_->length(first + static_cast<int32_t>(r)), n = std::max<int64_t>(c.n, 1);
    for (int64_t i = 0; i < n; ++i) {
      ids_[r * T + i] = c.n > 0 ? c.ids[i] : 0;
      positions_[r * T + i] = P + i;
    }
    seqlens_[r] = static_cast<int32_t>(P + n - 1);
    news_[r] = static_cast<int32_t>(n);
    source_of_[r] = c.source;
    total_ = std::max(total_, static_cast<int32_t>(P + n));
  }
  if (logits_.size() < R * T * vocab_) logits_.resize(R * T * vocab_);
}

// Per layer: past key and value over the rows' blocks (contract v4: all slots from 0; batch 1: the
// row's slot), present_* over the same memory, then the cross views (all encoder outputs, or the
// row's). The per-call inputs and output 0 are placeholders, bound per call.
void RowsDecoder::MakeViews(const ViewKey& key) {
  const Ort::MemoryInfo& mem = model_.cpu_memory;
  const ModelDims& d = model_.config.dims;
  const KvShape& ks = cache_->shape();
  const int64_t C = cache_->capacity(), H = d.n_heads, R = key.rows;
  const std::array<int64_t, 4> cache_shape = {R, H, C, ks.row_dims()};
  const int64_t S = model_.rows_contract ? sources_ : 1;
  const std::array<int64_t, 4> cross_shape = {S, H, d.n_latents, d.head_dim};
  views_ = key;
  in_values_.clear();
  out_values_.clear();
  for (size_t i = 0; i < PerCallInputs(); ++i) in_values_.emplace_back(nullptr);
  out_values_.emplace_back(nullptr);
  const auto type = KvOnnxType(ks.precision);
  const size_t bytes = static_cast<size_t>(R * cache_->slot_bytes());
  for (int64_t l = 0; l < d.n_layers; ++l)
    for (int kv = 0; kv < 2; ++kv) {
      void* past = cache_->slot_block(l, kv, key.first);
      out_values_.push_back(Ort::Value::CreateTensor(mem, past, bytes, cache_shape.data(), 4, type));
      in_values_.push_back(Ort::Value::CreateTensor(mem, past, bytes, cache_shape.data(), 4, type));
    }
  const int64_t slice = CrossSliceBytes(model_);
  for (int64_t lk = 0; lk < 2 * d.n_layers; ++lk) {
    unsigned char* at = cross_.data() + (lk * sources_ + std::max(key.source, 0)) * slice;
    in_values_.push_back(
        Ort::Value::CreateTensor(mem, at, static_cast<size_t>(S * slice), cross_shape.data(), 4, model_.cross_type));
  }
}

// ids, positions [R, T]; seqlens_k [R]; total length (scalar); contract v4: new_positions and
// cross_source [R].
void RowsDecoder::BindCallInputs(int64_t R, int64_t T) {
  const Ort::MemoryInfo& mem = model_.cpu_memory;
  const std::array<int64_t, 2> tok_shape = {R, T};
  const std::array<int64_t, 1> rows = {R};
  in_values_[0] = Ort::Value::CreateTensor<int64_t>(mem, ids_.data(), R * T, tok_shape.data(), 2);
  in_values_[1] = Ort::Value::CreateTensor<int64_t>(mem, positions_.data(), R * T, tok_shape.data(), 2);
  in_values_[2] = Ort::Value::CreateTensor<int32_t>(mem, seqlens_.data(), R, rows.data(), 1);
  in_values_[3] = Ort::Value::CreateTensor<int32_t>(mem, &total_, 1, nullptr, 0);
  if (!model_.rows_contract) return;
  in_values_[4] = Ort::Value::CreateTensor<int32_t>(mem, news_.data(), R, rows.data(), 1);
  in_values_[5] = Ort::Value::CreateTensor<int32_t>(mem, source_of_.data(), R, rows.data(), 1);
}

void RowsDecoder::KeepLogits(int32_t first, const std::vector<Chunk>& chunks, int64_t T) {
  for (size_t r = 0; r < chunks.size(); ++r) {
    const Chunk& c = chunks[r];
    if (c.n == 0 || !c.last) continue;
    const float* from = logits_.data() + (static_cast<int64_t>(r) * T + c.n - 1) * vocab_;
    std::copy(from, from + vocab_, row_logits_.data() + (first + static_cast<int64_t>(r)) * vocab_);
  }
}

}  // namespace silk
