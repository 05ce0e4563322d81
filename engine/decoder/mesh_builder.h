// Turns what the grammar accepted into a mesh: per component, decoded adjacency -> oriented
// faces (tokenizer face recovery, spec §10.6), then hole detection / repair (spec §12.2).
// Also the incremental view: faces of the closed layers of the component being generated.
#pragma once
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "core/status.h"
#include "decoder/grammar.h"
#include "tokenizer/layered_stream.h"
#include "tokenizer/tokenizer.h"

namespace silk {

enum class HolePolicy : int32_t {
  kOff = 0,     // faces as recovered
  kReport = 1,  // find holes (loops of open edges), report them, change nothing
  kRepair = 2,  // also close loops of <= max_fill_loop edges whose chords are legal matrix edges
};

struct MeshBuildOptions {
  HolePolicy holes = HolePolicy::kOff;
  int32_t max_fill_loop = 8;  // longest hole loop repair triangulates
};

// One hole: a loop of open edges (each with one face) in one component.
struct HoleReport {
  int32_t component = 0;
  std::vector<int32_t> loop;   // mesh vertex indices, in the hole's winding
  std::vector<int32_t> layers; // layer of each loop vertex
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
};

// Mesh of the closed components of `stream` (an open last component is skipped unless
// include_open is true, then only its closed layers count: `closed_layers_of_last`).
StatusOr<DecodedMesh> BuildMesh(const LayeredStream& stream, const MeshBuildOptions& options,
                                MeshBuildReport* report, int32_t closed_layers_of_last = -1);

// Mesh of everything the grammar has closed so far: whole components plus the closed layers
// of the current one (incremental rebuild for progress display; recomputes the current
// component, so cost grows with its size).
StatusOr<DecodedMesh> BuildMeshSoFar(const Grammar& grammar, const MeshBuildOptions& options,
                                     MeshBuildReport* report);

// Structural guarantees of grammar.h, checked on a mesh: "" when they hold, else the first
// failure (edge with > 2 faces, directed edge twice, repeated corner/position, face spanning
// two components, component without faces).
std::string CheckMeshGuarantees(const DecodedMesh& mesh);

// True when every edge of every face has exactly two faces.
bool IsWatertight(const DecodedMesh& mesh);

}  // namespace silk
