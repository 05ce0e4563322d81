// SPDX-License-Identifier: MIT
// Surface guidance: occupancy of the encoder's points on the 128^3 grid, its exact squared
// Euclidean distance transform, and the K/O mask restriction with the nearest-cells fallback.
#include "runtime/sampling/surface_guide.h"

#include <algorithm>
#include <limits>

#include "tokenizer/packing/vertex_codec.h"
#include "tokenizer/vocabulary_layout.h"

namespace silk {

namespace {

// Larger than any real squared distance in the grid (3 * 127^2), small enough to add to.
constexpr int32_t kFar = 1 << 28;

void SetBit(std::vector<uint64_t>* bits, size_t i) { (*bits)[i >> 6] |= uint64_t{1} << (i & 63); }

// 64 bits of `bits` (n bits, n a multiple of 64) from bit `start` on; zeros outside [0, n).
uint64_t Window(const uint64_t* bits, int64_t n, int64_t start) {
  if (start >= n || start <= -64) return 0;
  if (start < 0) return bits[0] << (-start);
  const int64_t w = start >> 6, sh = start & 63;
  uint64_t r = bits[w] >> sh;
  if (sh && (w + 1) * 64 < n) r |= bits[w + 1] << (64 - sh);
  return r;
}

// Keeps the ids of [begin, end) in *mask whose bit in `within` (bit id - begin, n = end - begin
// bits) is set, word-parallel; when none is, the ones at the smallest distance2(id) (the rare
// slow path). Returns true on a fallback (ids of the range present, none within).
template <class DistanceOf>
bool RestrictRange(TokenMask* mask, int32_t begin, int32_t end, const uint64_t* within, DistanceOf distance2) {
  const int32_t wb = begin >> 6, we = (end - 1) >> 6;
  auto range_bits = [&](int32_t w) {
    uint64_t m = ~uint64_t{0};
    if (w == wb) m &= ~uint64_t{0} << (begin & 63);
    if (w == we && (end & 63)) m &= ~uint64_t{0} >> (64 - (end & 63));
    return m;
  };
  bool any = false, kept = false;
  for (int32_t w = wb; w <= we; ++w) {
    const uint64_t legal = mask->words()[w] & range_bits(w);
    any = any || legal;
    kept = kept || (legal & Window(within, end - begin, int64_t{w} * 64 - begin));
  }
  if (!any) return false;
  if (kept) {
    for (int32_t w = wb; w <= we; ++w)
      mask->AndWord(w, ~(range_bits(w) & ~Window(within, end - begin, int64_t{w} * 64 - begin)));
    return false;
  }
  int32_t best = std::numeric_limits<int32_t>::max();
  for (int32_t id = mask->Next(begin); id >= 0 && id < end; id = mask->Next(id + 1))
    best = std::min(best, distance2(id));
  for (int32_t id = mask->Next(begin); id >= 0 && id < end; id = mask->Next(id + 1))
    if (distance2(id) != best) mask->Reset(id);
  return true;
}

}  // namespace

void DistanceTransform1D(int32_t* f, int32_t n, int32_t stride) {
  constexpr int32_t kBins = SurfaceGuide::kBins;
  // Lower envelope of the parabolas (q - site)^2 + f(site) over the finite sites.
  int32_t g[kBins], v[kBins];  // n <= kBins: scratch on the stack (16,384 lines per pass)
  double z[kBins + 1];
  n = std::min(n, kBins);
  for (int32_t q = 0; q < n; ++q) g[q] = f[q * stride];
  int32_t k = -1;
  for (int32_t q = 0; q < n; ++q) {
    if (g[q] >= kFar) continue;
    if (k < 0) {
      k = 0;
      v[0] = q;
      z[0] = -std::numeric_limits<double>::infinity();
      z[1] = std::numeric_limits<double>::infinity();
      continue;
    }
    double s = 0;
    while (true) {
      const int32_t p = v[k];
      s = (static_cast<double>(g[q]) + double(q) * q - (static_cast<double>(g[p]) + double(p) * p)) / (2.0 * (q - p));
      if (s > z[k]) break;
      --k;  // z[0] is -inf, so k stays >= 0
    }
    ++k;
    v[k] = q;
    z[k] = s;
    z[k + 1] = std::numeric_limits<double>::infinity();
  }
  if (k < 0) return;  // no site on this line: every value stays far
  int32_t j = 0;
  for (int32_t q = 0; q < n; ++q) {
    while (z[j + 1] < q) ++j;
    const int32_t d = q - v[j];
    f[q * stride] = d * d + g[v[j]];
  }
}

SurfaceGuide::SurfaceGuide(const std::vector<float>& points, int32_t tolerance)
    : tolerance_(tolerance),
      dist2_(static_cast<size_t>(kBins) * kBins * kBins, kFar),
      block_dist2_(512, kFar),
      block_within_(512 / 64, 0),
      offset_within_(512 * 4096 / 64, 0) {
  for (size_t i = 0; i + 6 <= points.size(); i += 6)
    dist2_[Index(QuantizeCoord(points[i]), QuantizeCoord(points[i + 1]), QuantizeCoord(points[i + 2]))] = 0;
  for (int32_t x = 0; x < kBins; ++x)
    for (int32_t y = 0; y < kBins; ++y) DistanceTransform1D(&dist2_[Index(x, y, 0)], kBins, 1);
  for (int32_t x = 0; x < kBins; ++x)
    for (int32_t z = 0; z < kBins; ++z) DistanceTransform1D(&dist2_[Index(x, 0, z)], kBins, kBins);
  for (int32_t y = 0; y < kBins; ++y)
    for (int32_t z = 0; z < kBins; ++z) DistanceTransform1D(&dist2_[Index(0, y, z)], kBins, kBins * kBins);
  for (int32_t x = 0; x < kBins; ++x)
    for (int32_t y = 0; y < kBins; ++y)
      for (int32_t z = 0; z < kBins; ++z) {
        const int32_t block = (x >> 4) * 64 + (y >> 4) * 8 + (z >> 4);
        const int32_t d2 = dist2_[Index(x, y, z)];
        block_dist2_[block] = std::min(block_dist2_[block], d2);
        if (Within(d2))
          SetBit(&offset_within_, static_cast<size_t>(block) * 4096 + (x & 15) * 256 + (y & 15) * 16 + (z & 15));
      }
  for (int32_t b = 0; b < 512; ++b)
    if (Within(block_dist2_[b])) SetBit(&block_within_, static_cast<size_t>(b));
}

bool SurfaceGuide::RestrictBlocks(TokenMask* mask) const {
  return RestrictRange(mask, vocab::kKBegin, vocab::kKEnd, block_within_.data(),
                       [&](int32_t id) { return block_dist2_[id - vocab::kKBegin]; });
}

bool SurfaceGuide::RestrictOffsets(int32_t block_id, TokenMask* mask) const {
  const uint64_t* within = offset_within_.data() + static_cast<size_t>(block_id - vocab::kKBegin) * (4096 / 64);
  return RestrictRange(mask, vocab::kOBegin, vocab::kOEnd, within,
                       [&](int32_t id) { return CellDistance2(VertexOfTokens(block_id, id)); });
}

}  // namespace silk
