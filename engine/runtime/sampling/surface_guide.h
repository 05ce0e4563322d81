// SPDX-License-Identifier: MIT
// SurfaceGuide: keeps generated vertices near the input surface by masking block (K) and offset
// (O) ids whose grid cells are farther than a tolerance from every cell holding an input point.
#pragma once
#include <cstdint>
#include <vector>

#include "decoder/token_mask.h"
#include "tokenizer/cleanup/quantize.h"

namespace silk {

// Built once per generation from the encoder's points (rows of 6 floats in the model frame,
// xyz first). Each point marks the cell the tokenizer's own QuantizeCoord puts it in, so grid
// cells and generated vertices agree. Distances are exact Euclidean distances in cells from a
// cell to the nearest marked cell (separable squared-distance transform, Felzenszwalb &
// Huttenlocher 2012), kept squared as integers; tolerance t keeps cells with d^2 <= t^2.
class SurfaceGuide {
 public:
  static constexpr int32_t kBins = 128;

  SurfaceGuide(const std::vector<float>& points, int32_t tolerance);

  int32_t tolerance() const { return tolerance_; }
  // Squared distance (cells^2) of a cell to the nearest occupied cell.
  int32_t CellDistance2(const QVec& q) const { return dist2_[Index(q.x, q.y, q.z)]; }
  // Smallest squared distance over the 16^3 cells of block b (0..511).
  int32_t BlockDistance2(int32_t block) const { return block_dist2_[block]; }
  bool Within(int32_t d2) const { return d2 <= tolerance_ * tolerance_; }

  // Restricts the K ids of *mask (any O ids: `block_id` is the K id just taken) to those within
  // the tolerance; when none is, keeps the legal ones at the smallest distance (returns true:
  // a fallback). Ids of other kinds are left alone, so the mask never empties and the grammar's
  // choice between a vertex and anything else is untouched.
  bool RestrictBlocks(TokenMask* mask) const;
  bool RestrictOffsets(int32_t block_id, TokenMask* mask) const;

 private:
  static int32_t Index(int32_t x, int32_t y, int32_t z) { return (x * kBins + y) * kBins + z; }
  int32_t tolerance_;
  std::vector<int32_t> dist2_;        // kBins^3
  std::vector<int32_t> block_dist2_;  // 512
  // Within the tolerance, as bits in token order (the per-token test is one bit): blocks, and
  // each block's 4,096 offsets (block * 4096 + offset).
  std::vector<uint64_t> block_within_, offset_within_;
};

// Squared Euclidean distance transform along one line of n values in place (f: 0 on sites, a
// large value elsewhere); n <= 128. Exposed for the tests.
void DistanceTransform1D(int32_t* f, int32_t n, int32_t stride);

}  // namespace silk
