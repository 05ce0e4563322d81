// SPDX-License-Identifier: MIT
// Union-find over face-component ids for the non-manifold pass (token_format.md §3.4 steps 3-4): only
// the partition it induces matters, so plain union by rank with path compression.
#pragma once
#include <cstdint>
#include <utility>
#include <vector>

namespace silk {

class UnionFind {
 public:
  explicit UnionFind(int32_t n = 0) {
    for (int32_t i = 0; i < n; ++i) Extend();
  }
  int32_t Extend() {
    parent_.push_back(static_cast<int32_t>(parent_.size()));
    rank_.push_back(1);
    return static_cast<int32_t>(parent_.size()) - 1;
  }
  int32_t Find(int32_t a) {
    int32_t r = a;
    while (parent_[static_cast<size_t>(r)] != r) r = parent_[static_cast<size_t>(r)];
    while (parent_[static_cast<size_t>(a)] != r) {
      const int32_t next = parent_[static_cast<size_t>(a)];
      parent_[static_cast<size_t>(a)] = r;
      a = next;
    }
    return r;
  }
  void Union(int32_t a, int32_t b) {
    int32_t ra = Find(a), rb = Find(b);
    if (ra == rb) return;
    if (rank_[static_cast<size_t>(ra)] < rank_[static_cast<size_t>(rb)]) std::swap(ra, rb);
    parent_[static_cast<size_t>(rb)] = ra;
    if (rank_[static_cast<size_t>(ra)] == rank_[static_cast<size_t>(rb)]) ++rank_[static_cast<size_t>(ra)];
  }
  int32_t size() const { return static_cast<int32_t>(parent_.size()); }

 private:
  std::vector<int32_t> parent_;
  std::vector<int32_t> rank_;
};

}  // namespace silk
