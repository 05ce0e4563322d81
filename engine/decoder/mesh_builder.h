// SPDX-License-Identifier: MIT
// Turns what the grammar accepted into a mesh: per component, the tokenizer's assembly
// (component_mesh: adjacency -> oriented faces, token_format.md §10.6), then hole detection / repair (spec
// §12.2) and the vertex-fan rule (vertex_fan_rules.h). Also the incremental view: faces of the
// closed layers of the component being generated, reusing components already built.
#pragma once
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "core/status.h"
#include "decoder/grammar.h"
#include "tokenizer/component_mesh.h"
#include "tokenizer/layering/layered_stream.h"
#include "tokenizer/tokenizer.h"

namespace silk {

enum class HolePolicy : int32_t {
  kOff = 0,     // faces as recovered
  kReport = 1,  // find holes (loops of open edges), report them, change nothing
  kRepair = 2,  // also close loops of <= max_fill_loop edges whose chords are legal matrix edges
};

// Vertices whose faces form two or more fans (docs/grammar.md "Vertex fans").
enum class VertexFanPolicy : int32_t {
  kResolve = 0,  // the guarantee: close the gaps (under HolePolicy::kRepair), split the rest
  kKeep = 1,     // faithful to the tokens (what DecodeTokens gives)
};

struct MeshBuildOptions {
  HolePolicy holes = HolePolicy::kOff;
  int32_t max_fill_loop = 8;  // longest hole loop repair triangulates
  VertexFanPolicy vertex_fans = VertexFanPolicy::kResolve;
  friend bool operator==(const MeshBuildOptions& a, const MeshBuildOptions& b) {
    return a.holes == b.holes && a.max_fill_loop == b.max_fill_loop && a.vertex_fans == b.vertex_fans;
  }
};

// One hole: a loop of open edges (each with one face) in one component.
struct HoleReport {
  int32_t component = 0;
  std::vector<int32_t> loop;    // mesh vertex indices, in the hole's winding
  std::vector<int32_t> layers;  // layer of each loop vertex
  bool repaired = false;
  // Chords added by the repair, as the matrix entries (1s predicted as 0s) they stand for:
  // "self L i j" or "between L i j" (layer-local indices; j in layer L-1 for between).
  std::vector<std::string> added_edges;
};

struct MeshBuildReport {
  std::vector<HoleReport> holes;
  std::vector<WindowFinding> window_findings;  // copied from the grammar (kUnion)
  int32_t faces_added = 0;
  int32_t open_edges_before = 0, open_edges_after = 0;
  int32_t dropped_degenerate = 0;  // zero-area (collinear) recovered faces dropped
  // Vertex-fan rule: vertices found with several fans, gap faces added, vertices split and
  // the copies the splits appended.
  int32_t nonmanifold_vertices = 0, fan_gaps_closed = 0, vertices_split = 0, vertex_copies = 0;
  void Add(const MeshBuildReport& o);  // counters and holes of another part (findings not)
};

// Closed components already built, reused by BuildMeshSoFar (valid while the grammar's tokens
// up to the last cached component are unchanged and the options are the same).
struct MeshBuildCache {
  MeshBuildOptions options;
  std::vector<int32_t> tokens;                     // the grammar's tokens when the cache was last extended
  std::vector<TokenizerComponentMesh> components;  // final meshes of components 0..n-1 (rules applied)
  std::vector<MeshBuildReport> reports;            // their report parts
};

// Mesh of the closed components of `stream` (an open last component is skipped unless
// include_open is true, then only its closed layers count: `closed_layers_of_last`).
StatusOr<TokenizerDecodedMesh> BuildMesh(const LayeredStream& stream, const MeshBuildOptions& options,
                                         MeshBuildReport* report, int32_t closed_layers_of_last = -1);

// One component through the shared assembly and the hole / vertex-fan rules (`base`: the
// component's first vertex in the whole mesh, for hole reports).
StatusOr<TokenizerComponentMesh> BuildComponentMesh(const StreamComponent& comp, int32_t closed_layers, int32_t ci,
                                                    int32_t base, const MeshBuildOptions& options,
                                                    MeshBuildReport* report);

// Mesh of everything the grammar has closed so far: whole components plus the closed layers
// of the current one. With a cache, closed components are built once and reused; only the
// open component (and those closed since the last call) are rebuilt.
StatusOr<TokenizerDecodedMesh> BuildMeshSoFar(const Grammar& grammar, const MeshBuildOptions& options,
                                              MeshBuildReport* report, MeshBuildCache* cache = nullptr);

// Structural guarantees of grammar.h, checked on a mesh: "" when they hold, else the first
// failure (edge with > 2 faces, directed edge twice, repeated corner/position, face spanning
// two components, component without faces, two faces on the same three corners, vertex whose
// faces form two or more fans).
std::string CheckMeshGuarantees(const TokenizerDecodedMesh& mesh);

// True when every edge of every face has exactly two faces (mesh_checks' verdict).
bool IsWatertight(const TokenizerDecodedMesh& mesh);

}  // namespace silk
