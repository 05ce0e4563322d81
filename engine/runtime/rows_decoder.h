// SPDX-License-Identifier: MIT
// RowsDecoder: feeds the known tokens of many sequences ("rows") to decoder.onnx together, one call
// per chunk for all rows (decoder contract v4: every weight read once per call for all rows), over a
// RowsKvCache. A row's ids go in chunks of at most max_chunk; with the ai.silk kernels a row's logits
// are bit for bit its logits alone, however its ids are cut into feeds. A call runs at its longest
// row's count (shorter rows padded): CandidateRows feeds every row the same count. A decoder before
// contract v4 (batch 1) runs the rows one after another over the same cache.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "runtime/decoder_runner.h"
#include "runtime/model/model_impl.h"
#include "runtime/rows_kv_cache.h"

namespace silk {

// One row's part of a Feed: n ids at positions cache.length(slot) on.
struct RowFeed {
  int32_t slot = 0;
  const int32_t* ids = nullptr;
  int64_t n = 0;
  int32_t source = 0;       // which encoder output (SetSource) the row attends to
  bool keep_logits = true;  // false: more of the row's ids follow in a later Feed (no logits kept)
};

class RowsDecoder {
 public:
  // The cache must be reserved with the model's KvShape; it outlives the decoder.
  RowsDecoder(const Model::Impl& model, RowsKvCache* cache, int64_t max_chunk = kDecoderChunk);

  // Encoder output `index` of `count` ([L, 2, H, M, D] of the model's cross_type, RunEncoder's):
  // copied in, so the caller's tensor may go. SetSources(count) first (keeps none).
  void SetSources(int32_t count);
  void SetSource(int32_t index, const void* cross_kv);

  // Feeds every row's ids (distinct slots); afterwards logits(slot) holds each row's next-token
  // logits after its last id (rows with keep_logits). With the ai.silk kernels (contract v4) a
  // position's logits and cache do not depend on how its row's ids were cut into feeds. Counts the calls each row took
  // part in (calls(slot)).
  Status Feed(const std::vector<RowFeed>& rows);
  const float* logits(int32_t slot) const { return row_logits_.data() + slot * vocab_; }
  int64_t calls() const { return calls_; }                   // decoder.onnx runs in all
  int64_t positions() const { return positions_computed_; }  // R x T summed over the runs (padding included)

 private:
  struct Chunk {  // a row's part of one call
    const int32_t* ids = nullptr;
    int64_t n = 0;  // 0: a placeholder row (a slot below the call's last with nothing to feed)
    int32_t source = 0;
    bool last = false;  // the row's last chunk: its logits are kept
  };
  struct ViewKey {
    const void* data = nullptr;
    int64_t capacity = 0, rows = 0;
    int32_t first = -1, source = -1;  // batch-1 decoders: the row's slot and encoder output
    bool operator==(const ViewKey& o) const {
      return data == o.data && capacity == o.capacity && rows == o.rows && first == o.first && source == o.source;
    }
  };
  Status CheckRows(const std::vector<RowFeed>& rows) const;
  // One decoder.onnx run for slots [first, first + chunks.size()) (contract v4: first = 0).
  Status Call(int32_t first, const std::vector<Chunk>& chunks);
  void Stage(int32_t first, const std::vector<Chunk>& chunks, int64_t T);
  void MakeViews(const ViewKey& key);
  void BindCallInputs(int64_t R, int64_t T);
  void KeepLogits(int32_t first, const std::vector<Chunk>& chunks, int64_t T);
  size_t PerCallInputs() const { return model_.rows_contract ? 6 : 4; }

  const Model::Impl& model_;
  RowsKvCache* cache_;
  int64_t max_chunk_, vocab_;
  int32_t sources_ = 0;
  std::vector<unsigned char> cross_;  // [L, 2, S, H, M, D] of the cross type
  std::vector<std::string> in_names_, out_names_;
  std::vector<const char*> in_ptrs_, out_ptrs_;
  std::vector<int64_t> ids_, positions_;             // [R, T]
  std::vector<int32_t> seqlens_, news_, source_of_;  // [R]
  int32_t total_ = 0;
  std::vector<Ort::Value> in_values_, out_values_;
  ViewKey views_;
  std::vector<float> logits_;      // [R, T, V], the bound output
  std::vector<float> row_logits_;  // [slots, V]
  int64_t calls_ = 0, positions_computed_ = 0;
};

}  // namespace silk
