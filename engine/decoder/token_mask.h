// SPDX-License-Identifier: MIT
// TokenMask: the set of legal ids over the whole model vocabulary (format ids, EOS, PAD) as a
// bitset, so a sampler can mask logits with one pass and the grammar can OR class ranges.
#pragma once
#include <array>
#include <cstdint>

#include "tokenizer/vocabulary_layout.h"

namespace silk {

class TokenMask {
 public:
  static constexpr int32_t kBits = vocab::k_model_vocab_size;
  static constexpr int32_t kWords = (kBits + 63) / 64;

  void Clear() { words_.fill(0); }
  void Set(int32_t id) { words_[id >> 6] |= uint64_t{1} << (id & 63); }
  void Reset(int32_t id) { words_[id >> 6] &= ~(uint64_t{1} << (id & 63)); }
  bool Test(int32_t id) const { return id >= 0 && id < kBits && ((words_[id >> 6] >> (id & 63)) & 1) != 0; }
  // Sets ids [begin, end).
  void SetRange(int32_t begin, int32_t end) {
    if (begin >= end) return;
    int32_t wb = begin >> 6, we = (end - 1) >> 6;
    uint64_t lo = ~uint64_t{0} << (begin & 63);
    uint64_t hi = ~uint64_t{0} >> (63 - ((end - 1) & 63));
    if (wb == we) {
      words_[wb] |= lo & hi;
      return;
    }
    words_[wb] |= lo;
    for (int32_t w = wb + 1; w < we; ++w) words_[w] = ~uint64_t{0};
    words_[we] |= hi;
  }
  int32_t Count() const {
    int32_t c = 0;
    for (uint64_t w : words_) c += __builtin_popcountll(w);
    return c;
  }
  bool Empty() const {
    for (uint64_t w : words_)
      if (w) return false;
    return true;
  }
  // The only set id, or -1 when zero or several ids are set.
  int32_t Single() const {
    int32_t found = -1;
    for (int32_t w = 0; w < kWords; ++w) {
      if (!words_[w]) continue;
      if (found >= 0 || (words_[w] & (words_[w] - 1))) return -1;
      found = w * 64 + __builtin_ctzll(words_[w]);
    }
    return found;
  }
  // Smallest set id >= from, or -1.
  int32_t Next(int32_t from) const {
    if (from >= kBits) return -1;
    int32_t w = from >> 6;
    uint64_t cur = words_[w] & (~uint64_t{0} << (from & 63));
    while (true) {
      if (cur) return w * 64 + __builtin_ctzll(cur);
      if (++w >= kWords) return -1;
      cur = words_[w];
    }
  }
  const std::array<uint64_t, kWords>& words() const { return words_; }
  // Clears the bits of word w that are clear in `keep` (word-parallel filters).
  void AndWord(int32_t w, uint64_t keep) { words_[w] &= keep; }

 private:
  std::array<uint64_t, kWords> words_{};
};

}  // namespace silk
