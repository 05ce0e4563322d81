// Surface guidance: occupancy of the encoder's points on the 128^3 grid, its exact squared
// Euclidean distance transform, and the K/O mask restriction with the nearest-cells fallback.
#include "runtime/surface_guide.h"

#include <algorithm>
#include <limits>

#include "tokenizer/vertex_codec.h"
#include "tokenizer/vocabulary_layout.h"

namespace silk {

namespace {

// Larger than any real squared distance in the grid (3 * 127^2), small enough to add to.
constexpr int32_t kFar = 1 << 28;

// Keeps the ids of [begin, end) in *mask whose distance is within the tolerance, or the nearest
// ones when none is. Returns true on a fallback (ids of the range present, none within).
template <class DistanceOf>
bool RestrictRange(TokenMask* mask, int32_t begin, int32_t end, int32_t tolerance2, DistanceOf distance2) {
  int32_t best = std::numeric_limits<int32_t>::max();
  bool any = false, within = false;
  for (int32_t id = mask->Next(begin); id >= 0 && id < end; id = mask->Next(id + 1)) {
    const int32_t d2 = distance2(id);
    any = true;
    within = within || d2 <= tolerance2;
    best = std::min(best, d2);
  }
  if (!any) return false;
  const int32_t keep = within ? tolerance2 : best;
  for (int32_t id = mask->Next(begin); id >= 0 && id < end; id = mask->Next(id + 1))
    if (distance2(id) > keep) mask->Reset(id);
  return !within;
}

}  // namespace

void DistanceTransform1D(int32_t* f, int32_t n, int32_t stride) {
  // Lower envelope of the parabolas (q - site)^2 + f(site) over the finite sites.
  std::vector<int32_t> g(n), v(n);
  std::vector<double> z(n + 1);
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
    : tolerance_(tolerance), dist2_(static_cast<size_t>(kBins) * kBins * kBins, kFar), block_dist2_(512, kFar) {
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
        int32_t& b = block_dist2_[(x >> 4) * 64 + (y >> 4) * 8 + (z >> 4)];
        b = std::min(b, dist2_[Index(x, y, z)]);
      }
}

bool SurfaceGuide::RestrictBlocks(TokenMask* mask) const {
  return RestrictRange(mask, vocab::kKBegin, vocab::kKEnd, tolerance_ * tolerance_,
                       [&](int32_t id) { return block_dist2_[id - vocab::kKBegin]; });
}

bool SurfaceGuide::RestrictOffsets(int32_t block_id, TokenMask* mask) const {
  return RestrictRange(mask, vocab::kOBegin, vocab::kOEnd, tolerance_ * tolerance_,
                       [&](int32_t id) { return CellDistance2(VertexOfTokens(block_id, id)); });
}

}  // namespace silk
