// SPDX-License-Identifier: MIT
// The tokenizer's public C++ entry points: mesh -> Mesh Silksong token ids (bit-exact with
// the reference, docs/token_format.md) and ids -> mesh (every face the tokens can carry).
#pragma once
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "core/status.h"
#include "io/io_mesh.h"
#include "tokenizer/cleanup/quantize.h"
#include "tokenizer/layering/layered_stream.h"

namespace silk {

struct EncodeOptions {
  bool nonmanifold_processing = true;  // token_format.md §3; off = refuse non-manifold input
};

// Wall time per encoder phase, seconds.
struct EncodePhaseTimes {
  double quantize_cleanup = 0, nonmanifold = 0, orientation = 0, components = 0, layering = 0, codecs = 0, packing = 0;
};

struct EncodeStats {
  int32_t input_vertices = 0, input_faces = 0;
  int32_t merged_vertices = 0;  // input vertices that became duplicates (§2.3)
  int32_t dropped_degenerate_faces = 0, dropped_duplicate_faces = 0;
  int32_t nonmanifold_copies = 0;  // vertices added by §3
  int32_t flipped_faces = 0;       // faces reversed by §3.7
  int32_t components_found = 0, components_encoded = 0, components_dropped_small = 0;
  int32_t processed_vertices = 0;  // distinct vertices used by emitted faces
  int32_t processed_faces = 0;     // faces of emitted components
  int32_t emitted_vertices = 0;    // vertices in the token stream
  int32_t encodable_faces = 0;     // processed faces whose 3 edges the stream carries
  int32_t layers = 0;              // over all components (layer 0 included)
  int32_t max_layer_size = 0;
  int32_t max_layer_count = 0;  // largest per-component layer count
  int64_t tokens = 0;
  EncodePhaseTimes times;
};

struct EncodeResult {
  std::vector<int32_t> tokens;  // no BOS/EOS/PAD (token_format.md §8.3)
  LayeredStream stream;
  // Faces of the emitted components in encoder winding, as grid coordinates.
  std::vector<std::array<QVec, 3>> processed_faces;
  // Subset of processed_faces whose edges the stream does not carry (token_format.md §5.4).
  std::vector<std::array<QVec, 3>> unencodable_faces;
  EncodeStats stats;
};

// `normalized` must already be normalised to [-1, 1] (NormalizeMesh in mesh/), finite.
// Refusals come back as Status kRefused with a named reason (tokenizer/refusal.h).
StatusOr<EncodeResult> EncodeMesh(const IoMesh& normalized, const EncodeOptions& options = {});

struct DecodeOptions {
  // Reserved for decoder variants; the default recovers every face the tokens carry.
  bool official_faces = false;  // true: the reference decoder's face rule (token_format.md §10.3)
};

// The mesh the tokens carry, in grid coordinates (docs/mesh_types.md): what DecodeTokens gives and
// the decoder's BuildMesh builds; the runtime and the C API turn it into an IoMesh.
struct TokenizerDecodedMesh {
  std::vector<QVec> positions;                // one per emitted vertex, reading order
  std::vector<std::array<int32_t, 3>> faces;  // indices into positions, oriented
  std::vector<int32_t> face_component;        // component index per face
  std::vector<int32_t> vertex_component;      // component index per vertex
  int32_t components = 0;
};

// Parses ids into components/layers/vertices (token_reader). Strict: any id out of place
// is an error naming its position.
StatusOr<LayeredStream> ReadTokenStream(const std::vector<int32_t>& ids);
// ids -> mesh: parse, rebuild adjacency, recover faces.
StatusOr<TokenizerDecodedMesh> DecodeTokens(const std::vector<int32_t>& ids, const DecodeOptions& options = {});

}  // namespace silk
