// SPDX-License-Identifier: MIT
// Vertex tokens (token_format.md §8.1): a grid position <-> block token K + offset token O.
#pragma once
#include <cstdint>

#include "tokenizer/cleanup/quantize.h"
#include "tokenizer/vocabulary_layout.h"

namespace silk {

inline int32_t BlockTokenOf(const QVec& q) { return vocab::kKBegin + (q.x >> 4) * 64 + (q.y >> 4) * 8 + (q.z >> 4); }
inline int32_t OffsetTokenOf(const QVec& q) { return vocab::kOBegin + (q.x & 15) * 256 + (q.y & 15) * 16 + (q.z & 15); }
// Inverse; block_id/offset_id must lie in the K/O ranges.
inline QVec VertexOfTokens(int32_t block_id, int32_t offset_id) {
  const int32_t b = block_id - vocab::kKBegin, o = offset_id - vocab::kOBegin;
  return QVec{(b / 64) * 16 + o / 256, ((b / 8) % 8) * 16 + (o / 16) % 16, (b % 8) * 16 + o % 16};
}

}  // namespace silk
