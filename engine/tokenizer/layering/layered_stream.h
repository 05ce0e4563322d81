// SPDX-License-Identifier: MIT
// LayeredStream: the token sequence's structure, halfway between a mesh and ids.
// Encoding is  mesh -> LayeredStream (layering + matrix codecs) -> ids (token_writer);
// decoding is  ids -> LayeredStream (token_reader) -> adjacency -> faces (face_recovery).
#pragma once
#include <cstdint>
#include <vector>

#include "tokenizer/cleanup/quantize.h"

namespace silk {

// One between-layer token: start column s and case c (token_format.md §7.2), id = 459 + 26*s + c.
struct BetweenToken {
  int32_t start = 0;
  int32_t kase = 0;
  friend bool operator==(const BetweenToken& a, const BetweenToken& b) {
    return a.start == b.start && a.kase == b.kase;
  }
};

struct StreamVertex {
  QVec pos;
  int32_t window = 0;                 // S token value w (id - 203), 8 bits (token_format.md §6)
  std::vector<int32_t> extras;        // X token values e (id - 3), increasing (token_format.md §6)
  std::vector<BetweenToken> between;  // B tokens in increasing start (token_format.md §7)
};

struct StreamLayer {
  std::vector<StreamVertex> vertices;
};

struct StreamComponent {
  std::vector<StreamLayer> layers;  // layers[0] holds exactly the root (V tokens only)
};

struct LayeredStream {
  std::vector<StreamComponent> components;
};

// Decoded adjacency of one layer, in layer-local indices.
struct LayerAdjacency {
  // Self-layer pairs (i, j), i < j, sorted.
  std::vector<std::pair<int32_t, int32_t>> self_edges;
  // Between-layer pairs (i in this layer, j in the previous layer), sorted.
  std::vector<std::pair<int32_t, int32_t>> between_edges;
};

}  // namespace silk
