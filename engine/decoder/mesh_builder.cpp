// SPDX-License-Identifier: MIT
// Mesh assembly from accepted layers, hole detection and repair by loop triangulation
// (token_format.md §12.2: a hole shows up as missing matrix 1s; a loop of open edges between two
// adjacent layers is closed by the chords a consistent matrix would have had).
#include "decoder/mesh_builder.h"

#include <algorithm>
#include <map>
#include <set>
#include <unordered_map>

#include "tokenizer/cleanup/collinear.h"
#include "decoder/vertex_fan_rules.h"
#include "mesh/mesh_checks.h"
#include "mesh/vertex_fans.h"

namespace silk {
namespace {

uint64_t Key(int32_t a, int32_t b) {
  return (static_cast<uint64_t>(static_cast<uint32_t>(a)) << 32) | static_cast<uint32_t>(b);
}

// Open loops of one component's faces (local indices): chains of reversed open half-edges.
std::vector<std::vector<int32_t>> OpenLoops(const std::vector<std::array<int32_t, 3>>& faces, int32_t* open_edges) {
  std::unordered_map<uint64_t, int32_t> directed;
  for (const auto& f : faces)
    for (int k = 0; k < 3; ++k) ++directed[Key(f[k], f[(k + 1) % 3])];
  std::multimap<int32_t, int32_t> next;  // hole half-edge b -> a for open a -> b
  int32_t open = 0;
  for (const auto& f : faces)
    for (int k = 0; k < 3; ++k) {
      const int32_t a = f[k], b = f[(k + 1) % 3];
      if (!directed.count(Key(b, a))) {
        next.emplace(b, a);
        ++open;
      }
    }
  if (open_edges) *open_edges += open;
  std::vector<std::vector<int32_t>> loops;
  while (!next.empty()) {
    auto it = next.begin();
    const int32_t start = it->first;
    std::vector<int32_t> loop{start};
    int32_t cur = it->second;
    next.erase(it);
    bool closed = false;
    for (int32_t guard = 0; guard < 4096; ++guard) {
      if (cur == start) {
        closed = true;
        break;
      }
      loop.push_back(cur);
      auto nt = next.find(cur);
      if (nt == next.end()) break;
      cur = nt->second;
      next.erase(nt);
    }
    if (closed) loops.push_back(std::move(loop));
  }
  return loops;
}

// Fan-triangulates `loop` (hole winding) from the first apex whose chords are new edges,
// join vertices of equal or adjacent layers, never two corners at one position and never
// a zero-area face.
bool FillLoop(const std::vector<int32_t>& loop, const TokenizerComponentMesh& cb, std::set<uint64_t>* edges,
              std::vector<std::array<int32_t, 3>>* faces, HoleReport* rep) {
  const int32_t k = static_cast<int32_t>(loop.size());
  std::set<int32_t> distinct(loop.begin(), loop.end());
  if (static_cast<int32_t>(distinct.size()) != k) return false;
  // A 3-loop that is the border of one existing face (an isolated triangle, or a face whose
  // three neighbours are missing) would be closed by that face reversed: a duplicate face, a
  // two-sided "pillow". Larger loops always fill with a new chord in every face.
  if (k == 3)
    for (const auto& f : *faces)
      if (std::set<int32_t>(f.begin(), f.end()) == distinct) return false;
  auto has = [&](int32_t a, int32_t b) { return edges->count(Key(std::min(a, b), std::max(a, b))) > 0; };
  for (int32_t apex = 0; apex < k; ++apex) {
    const int32_t v0 = loop[apex];
    bool ok = true;
    for (int32_t t = 2; t < k - 1 && ok; ++t) {
      const int32_t v = loop[(apex + t) % k];
      ok = !has(v0, v) && std::abs(cb.layer_of[v0] - cb.layer_of[v]) <= 1;
    }
    for (int32_t t = 1; t + 1 < k && ok; ++t) {
      const int32_t a = loop[(apex + t) % k], b = loop[(apex + t + 1) % k];
      // Distinct corners are not enough: a fill face must also have non-zero area
      // (guarantee: no degenerate face; found by grammar_fuzzer).
      ok = cb.positions[v0] != cb.positions[a] && cb.positions[v0] != cb.positions[b] &&
           cb.positions[a] != cb.positions[b] && !Collinear(cb.positions[v0], cb.positions[a], cb.positions[b]);
    }
    if (!ok) continue;
    for (int32_t t = 1; t + 1 < k; ++t) faces->push_back({v0, loop[(apex + t) % k], loop[(apex + t + 1) % k]});
    for (int32_t t = 2; t < k - 1; ++t) {
      const int32_t v = loop[(apex + t) % k];
      edges->insert(Key(std::min(v0, v), std::max(v0, v)));
      int32_t a = v0, b = v;
      if (cb.layer_of[a] < cb.layer_of[b]) std::swap(a, b);
      const bool self = cb.layer_of[a] == cb.layer_of[b];
      rep->added_edges.push_back(std::string(self ? "self " : "between ") + std::to_string(cb.layer_of[a]) + " " +
                                 std::to_string(cb.index_in_layer[a]) + " " + std::to_string(cb.index_in_layer[b]));
    }
    return true;
  }
  return false;
}

// token_format.md §12.2 hole policy on one component's faces (local indices).
void HandleHoles(TokenizerComponentMesh* cm, int32_t ci, int32_t base, const MeshBuildOptions& options,
                 MeshBuildReport* report) {
  auto& faces = cm->faces;
  int32_t open_before = 0;
  auto loops = OpenLoops(faces, &open_before);
  std::set<uint64_t> edges;
  for (const auto& f : faces)
    for (int k = 0; k < 3; ++k) edges.insert(Key(std::min(f[k], f[(k + 1) % 3]), std::max(f[k], f[(k + 1) % 3])));
  for (const auto& loop : loops) {
    HoleReport hr;
    hr.component = ci;
    for (int32_t v : loop) {
      hr.loop.push_back(v + base);
      hr.layers.push_back(cm->layer_of[v]);
    }
    if (options.holes == HolePolicy::kRepair && static_cast<int32_t>(loop.size()) <= options.max_fill_loop) {
      const size_t before = faces.size();
      hr.repaired = FillLoop(loop, *cm, &edges, &faces, &hr);
      if (report) report->faces_added += static_cast<int32_t>(faces.size() - before);
    }
    if (report) report->holes.push_back(std::move(hr));
  }
  if (report) {
    report->open_edges_before += open_before;
    int32_t open_after = 0;
    OpenLoops(faces, &open_after);
    report->open_edges_after += open_after;
  }
}

// The vertex-fan rule (vertex_fan_rules.h): gaps closed under kRepair, then splits; copies
// take the position, layer and in-layer index of the vertex they copy.
void HandleVertexFans(TokenizerComponentMesh* cm, const MeshBuildOptions& options, MeshBuildReport* report) {
  std::vector<int32_t> copy_of;
  VertexFanCounts counts;
  ResolveVertexFans(&cm->faces, cm->positions, cm->layer_of, options.holes == HolePolicy::kRepair, &copy_of, &counts);
  for (int32_t v : copy_of) {
    cm->positions.push_back(cm->positions[v]);
    cm->layer_of.push_back(cm->layer_of[v]);
    cm->index_in_layer.push_back(cm->index_in_layer[v]);
  }
  if (report) {
    report->nonmanifold_vertices += counts.nonmanifold_vertices;
    report->fan_gaps_closed += counts.gaps_closed;
    report->vertices_split += counts.vertices_split;
    report->vertex_copies += counts.vertex_copies;
  }
}

}  // namespace

StatusOr<TokenizerComponentMesh> BuildComponentMesh(const StreamComponent& comp, int32_t closed_layers, int32_t ci,
                                                    int32_t base, const MeshBuildOptions& options,
                                                    MeshBuildReport* report) {
  SILK_ASSIGN_OR_RETURN(TokenizerComponentMesh cm, AssembleComponentMesh(comp, closed_layers));
  if (report) report->dropped_degenerate += cm.dropped_degenerate;
  if (cm.positions.empty()) return cm;
  if (options.holes != HolePolicy::kOff) HandleHoles(&cm, ci, base, options, report);
  if (options.vertex_fans == VertexFanPolicy::kResolve) HandleVertexFans(&cm, options, report);
  return cm;
}

StatusOr<TokenizerDecodedMesh> BuildMesh(const LayeredStream& stream, const MeshBuildOptions& options,
                                         MeshBuildReport* report, int32_t closed_layers_of_last) {
  TokenizerDecodedMesh mesh;
  const int32_t nc = static_cast<int32_t>(stream.components.size());
  for (int32_t ci = 0; ci < nc; ++ci) {
    const int32_t closed = ci == nc - 1 ? closed_layers_of_last : -1;
    auto cm = BuildComponentMesh(stream.components[ci], closed, ci, static_cast<int32_t>(mesh.positions.size()),
                                 options, report);
    if (!cm.ok()) return cm.status().WithContext("component " + std::to_string(ci) + ": ");
    AppendComponentMesh(*cm, ci, &mesh);
  }
  mesh.components = nc;
  return mesh;
}

void MeshBuildReport::Add(const MeshBuildReport& o) {
  holes.insert(holes.end(), o.holes.begin(), o.holes.end());
  faces_added += o.faces_added;
  open_edges_before += o.open_edges_before;
  open_edges_after += o.open_edges_after;
  dropped_degenerate += o.dropped_degenerate;
  nonmanifold_vertices += o.nonmanifold_vertices;
  fan_gaps_closed += o.fan_gaps_closed;
  vertices_split += o.vertices_split;
  vertex_copies += o.vertex_copies;
}

namespace {
// The cache is usable when the options match and the grammar still holds the tokens it saw.
bool CacheValid(const MeshBuildCache& cache, const Grammar& grammar, const MeshBuildOptions& options) {
  const auto& t = grammar.tokens();
  return cache.options == options && cache.tokens.size() <= t.size() &&
         std::equal(cache.tokens.begin(), cache.tokens.end(), t.begin());
}
}  // namespace

StatusOr<TokenizerDecodedMesh> BuildMeshSoFar(const Grammar& grammar, const MeshBuildOptions& options,
                                              MeshBuildReport* report, MeshBuildCache* cache) {
  const bool open = grammar.phase() != GrammarPhase::kAfterE && grammar.phase() != GrammarPhase::kEnded &&
                    grammar.phase() != GrammarPhase::kStart;
  if (report) report->window_findings = grammar.window_findings();
  if (!cache) return BuildMesh(grammar.stream(), options, report, open ? grammar.closed_layers() : -1);
  if (!CacheValid(*cache, grammar, options)) *cache = MeshBuildCache{options, {}, {}, {}};
  const auto& comps = grammar.stream().components;
  const int32_t nc = static_cast<int32_t>(comps.size());
  const int32_t closed = open ? nc - 1 : nc;
  TokenizerDecodedMesh mesh;
  for (int32_t ci = 0; ci < nc; ++ci) {
    if (ci < static_cast<int32_t>(cache->components.size())) {
      if (report) report->Add(cache->reports[ci]);
      AppendComponentMesh(cache->components[ci], ci, &mesh);
      continue;
    }
    MeshBuildReport part;
    auto built = BuildComponentMesh(comps[ci], ci == closed ? grammar.closed_layers() : -1, ci,
                                    static_cast<int32_t>(mesh.positions.size()), options, &part);
    if (!built.ok()) return built.status().WithContext("component " + std::to_string(ci) + ": ");
    if (report) report->Add(part);
    AppendComponentMesh(*built, ci, &mesh);
    if (ci < closed) {
      cache->components.push_back(std::move(built).value());
      cache->reports.push_back(std::move(part));
    }
  }
  cache->tokens = grammar.tokens();
  mesh.components = nc;
  return mesh;
}

std::string CheckMeshGuarantees(const TokenizerDecodedMesh& mesh) {
  std::unordered_map<uint64_t, int32_t> undirected;
  std::set<uint64_t> directed;
  std::set<std::array<int32_t, 3>> corner_sets;
  std::vector<int32_t> faces_per_component(static_cast<size_t>(std::max(mesh.components, 0)), 0);
  for (size_t i = 0; i < mesh.faces.size(); ++i) {
    const auto& f = mesh.faces[i];
    const std::string at = "face " + std::to_string(i) + ": ";
    if (f[0] == f[1] || f[1] == f[2] || f[0] == f[2]) return at + "repeated corner";
    for (int k = 0; k < 3; ++k)
      if (f[k] < 0 || f[k] >= static_cast<int32_t>(mesh.positions.size())) return at + "corner out of range";
    if (mesh.positions[f[0]] == mesh.positions[f[1]] || mesh.positions[f[1]] == mesh.positions[f[2]] ||
        mesh.positions[f[0]] == mesh.positions[f[2]])
      return at + "two corners at one position";
    if (Collinear(mesh.positions[f[0]], mesh.positions[f[1]], mesh.positions[f[2]])) return at + "zero area";
    std::array<int32_t, 3> sorted = f;
    std::sort(sorted.begin(), sorted.end());
    if (!corner_sets.insert(sorted).second) return at + "duplicate of an earlier face (same corners)";
    const int32_t c = mesh.face_component[i];
    for (int k = 0; k < 3; ++k)
      if (mesh.vertex_component[f[k]] != c) return at + "corners of different components";
    if (c >= 0 && c < mesh.components) ++faces_per_component[c];
    for (int k = 0; k < 3; ++k) {
      const int32_t a = f[k], b = f[(k + 1) % 3];
      if (!directed.insert(Key(a, b)).second) return at + "directed edge used twice (orientation)";
      if (++undirected[Key(std::min(a, b), std::max(a, b))] > 2) return at + "edge with more than 2 faces";
    }
  }
  for (int32_t c = 0; c < mesh.components; ++c)
    if (faces_per_component[c] == 0) return "component " + std::to_string(c) + " has no face";
  const VertexFans fans = ComputeVertexFans(mesh.faces, static_cast<int32_t>(mesh.positions.size()));
  for (size_t v = 0; v < fans.fans_per_vertex.size(); ++v)
    if (fans.fans_per_vertex[v] > 1)
      return "vertex " + std::to_string(v) + ": its faces form " + std::to_string(fans.fans_per_vertex[v]) + " fans";
  return "";
}

bool IsWatertight(const TokenizerDecodedMesh& mesh) {
  return CheckFaces(mesh.faces, static_cast<int32_t>(mesh.positions.size())).watertight;
}

}  // namespace silk
