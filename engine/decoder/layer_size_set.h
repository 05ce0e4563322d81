// SPDX-License-Identifier: MIT
// LayerSizeSet: a set of candidate layer sizes N in [0, 255]. The grammar keeps the sizes at
// which the current layer could still be closed canonically (token_format.md §11.2 deferred rules).
#pragma once
#include <array>
#include <cstdint>

namespace silk {

class LayerSizeSet {
 public:
  void Clear() { w_.fill(0); }
  void Fill(int32_t lo, int32_t hi) {  // [lo, hi] inclusive
    Clear();
    for (int32_t n = lo; n <= hi; ++n) Set(n);
  }
  void Set(int32_t n) { w_[n >> 6] |= uint64_t{1} << (n & 63); }
  void Reset(int32_t n) { w_[n >> 6] &= ~(uint64_t{1} << (n & 63)); }
  bool Test(int32_t n) const { return n >= 0 && n < 256 && ((w_[n >> 6] >> (n & 63)) & 1); }
  bool Empty() const { return !(w_[0] | w_[1] | w_[2] | w_[3]); }
  int32_t Count() const {
    int32_t c = 0;
    for (uint64_t w : w_) c += __builtin_popcountll(w);
    return c;
  }
  // Keeps only values >= lo.
  void KeepAtLeast(int32_t lo) {
    for (int32_t i = 0; i < 4; ++i) {
      int32_t base = i * 64;
      if (lo <= base) break;
      if (lo >= base + 64)
        w_[i] = 0;
      else
        w_[i] &= ~uint64_t{0} << (lo - base);
    }
  }
  // Keeps only values <= hi.
  void KeepAtMost(int32_t hi) {
    for (int32_t i = 3; i >= 0; --i) {
      int32_t base = i * 64;
      if (hi >= base + 63) break;
      if (hi < base)
        w_[i] = 0;
      else
        w_[i] &= ~uint64_t{0} >> (63 - (hi - base));
    }
  }
  // Smallest member >= from, or -1.
  int32_t Next(int32_t from) const {
    if (from < 0) from = 0;
    if (from >= 256) return -1;
    int32_t i = from >> 6;
    uint64_t cur = w_[i] & (~uint64_t{0} << (from & 63));
    while (true) {
      if (cur) return i * 64 + __builtin_ctzll(cur);
      if (++i >= 4) return -1;
      cur = w_[i];
    }
  }
  // Largest member <= from, or -1.
  int32_t Prev(int32_t from) const {
    if (from < 0) return -1;
    if (from > 255) from = 255;
    int32_t i = from >> 6;
    uint64_t cur = w_[i] & (~uint64_t{0} >> (63 - (from & 63)));
    while (true) {
      if (cur) return i * 64 + 63 - __builtin_clzll(cur);
      if (--i < 0) return -1;
      cur = w_[i];
    }
  }
  int32_t Max() const {
    for (int32_t i = 3; i >= 0; --i)
      if (w_[i]) return i * 64 + 63 - __builtin_clzll(w_[i]);
    return -1;
  }
  // Number of members strictly greater than v.
  int32_t CountAbove(int32_t v) const {
    int32_t c = 0;
    for (int32_t i = 0; i < 4; ++i) {
      int32_t base = i * 64;
      if (v >= base + 63) continue;
      uint64_t m = (v < base) ? w_[i] : (w_[i] & (~uint64_t{0} << (v - base + 1)));
      c += __builtin_popcountll(m);
    }
    return c;
  }
  LayerSizeSet& operator&=(const LayerSizeSet& o) {
    for (int32_t i = 0; i < 4; ++i) w_[i] &= o.w_[i];
    return *this;
  }

 private:
  std::array<uint64_t, 4> w_{};
};

}  // namespace silk
