// Mesh assembly from accepted layers, hole detection and repair by loop triangulation
// (spec §12.2: a hole shows up as missing matrix 1s; a loop of open edges between two
// adjacent layers is closed by the chords a consistent matrix would have had).
#include "decoder/mesh_builder.h"

#include <algorithm>
#include <map>
#include <set>
#include <unordered_map>

#include "tokenizer/collinear.h"
#include "tokenizer/component_graph.h"
#include "tokenizer/face_recovery.h"
#include "tokenizer/layer_adjacency.h"

namespace silk {
namespace {

uint64_t Key(int32_t a, int32_t b) { return (static_cast<uint64_t>(static_cast<uint32_t>(a)) << 32) | static_cast<uint32_t>(b); }

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

struct ComponentBuild {
  ComponentLayers layers;
  std::vector<int32_t> layer_of, index_in_layer;
  std::vector<QVec> positions;
};

StatusOr<ComponentBuild> Layers(const StreamComponent& comp, int32_t closed_layers) {
  ComponentBuild cb;
  int32_t prev = 0;
  const int32_t count = closed_layers < 0 ? static_cast<int32_t>(comp.layers.size()) : closed_layers;
  for (int32_t l = 0; l < count; ++l) {
    std::vector<QVec> pos;
    for (size_t i = 0; i < comp.layers[l].vertices.size(); ++i) {
      pos.push_back(comp.layers[l].vertices[i].pos);
      cb.positions.push_back(comp.layers[l].vertices[i].pos);
      cb.layer_of.push_back(l);
      cb.index_in_layer.push_back(static_cast<int32_t>(i));
    }
    if (l > 0) {
      auto adj = DecodeLayerAdjacency(comp.layers[l], prev);
      if (!adj.ok()) return adj.status().WithContext("layer " + std::to_string(l) + ": ");
      cb.layers.adjacency.push_back(std::move(adj).value());
    }
    prev = static_cast<int32_t>(pos.size());
    cb.layers.layer_positions.push_back(std::move(pos));
  }
  return cb;
}

// Fan-triangulates `loop` (hole winding) from the first apex whose chords are new edges,
// join vertices of equal or adjacent layers, never two corners at one position and never
// a zero-area face.
bool FillLoop(const std::vector<int32_t>& loop, const ComponentBuild& cb, std::set<uint64_t>* edges,
              std::vector<std::array<int32_t, 3>>* faces, HoleReport* rep) {
  const int32_t k = static_cast<int32_t>(loop.size());
  std::set<int32_t> distinct(loop.begin(), loop.end());
  if (static_cast<int32_t>(distinct.size()) != k) return false;
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

Status AppendComponent(const StreamComponent& comp, int32_t closed_layers, int32_t ci, const MeshBuildOptions& options,
                       DecodedMesh* mesh, MeshBuildReport* report) {
  SILK_ASSIGN_OR_RETURN(ComponentBuild cb, Layers(comp, closed_layers));
  if (cb.positions.empty()) return Status::Ok();
  std::vector<std::array<int32_t, 3>> faces;
  if (cb.layers.layer_positions.size() >= 2) {
    SILK_ASSIGN_OR_RETURN(faces, RecoverComponentFaces(cb.layers));
  }
  // "No degenerate face": recovered faces are 3-cycles of edges, and the grammar refuses
  // zero-length edges; zero-area (collinear) triangles are dropped here.
  std::vector<std::array<int32_t, 3>> kept;
  for (const auto& f : faces) {
    if (Collinear(cb.positions[f[0]], cb.positions[f[1]], cb.positions[f[2]])) {
      if (report) ++report->dropped_degenerate;
      continue;
    }
    kept.push_back(f);
  }
  faces.swap(kept);
  if (options.holes != HolePolicy::kOff) {
    int32_t open_before = 0;
    auto loops = OpenLoops(faces, &open_before);
    std::set<uint64_t> edges;
    for (const auto& f : faces)
      for (int k = 0; k < 3; ++k) edges.insert(Key(std::min(f[k], f[(k + 1) % 3]), std::max(f[k], f[(k + 1) % 3])));
    const int32_t base = static_cast<int32_t>(mesh->positions.size());
    for (const auto& loop : loops) {
      HoleReport hr;
      hr.component = ci;
      for (int32_t v : loop) {
        hr.loop.push_back(v + base);
        hr.layers.push_back(cb.layer_of[v]);
      }
      if (options.holes == HolePolicy::kRepair && static_cast<int32_t>(loop.size()) <= options.max_fill_loop) {
        const size_t before = faces.size();
        hr.repaired = FillLoop(loop, cb, &edges, &faces, &hr);
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
  const int32_t base = static_cast<int32_t>(mesh->positions.size());
  for (const QVec& q : cb.positions) {
    mesh->positions.push_back(q);
    mesh->vertex_component.push_back(ci);
  }
  for (const auto& f : faces) {
    mesh->faces.push_back({f[0] + base, f[1] + base, f[2] + base});
    mesh->face_component.push_back(ci);
  }
  mesh->components = ci + 1;
  return Status::Ok();
}

}  // namespace

StatusOr<DecodedMesh> BuildMesh(const LayeredStream& stream, const MeshBuildOptions& options, MeshBuildReport* report,
                                int32_t closed_layers_of_last) {
  DecodedMesh mesh;
  const int32_t nc = static_cast<int32_t>(stream.components.size());
  for (int32_t ci = 0; ci < nc; ++ci) {
    const int32_t closed = ci == nc - 1 ? closed_layers_of_last : -1;
    Status st = AppendComponent(stream.components[ci], closed, ci, options, &mesh, report);
    if (!st.ok()) return st.WithContext("component " + std::to_string(ci) + ": ");
  }
  mesh.components = nc;
  return mesh;
}

StatusOr<DecodedMesh> BuildMeshSoFar(const Grammar& grammar, const MeshBuildOptions& options, MeshBuildReport* report) {
  const bool open = grammar.phase() != GrammarPhase::kAfterE && grammar.phase() != GrammarPhase::kEnded &&
                    grammar.phase() != GrammarPhase::kStart;
  if (report) report->window_findings = grammar.window_findings();
  return BuildMesh(grammar.stream(), options, report, open ? grammar.closed_layers() : -1);
}

std::string CheckMeshGuarantees(const DecodedMesh& mesh) {
  std::unordered_map<uint64_t, int32_t> undirected;
  std::set<uint64_t> directed;
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
  return "";
}

bool IsWatertight(const DecodedMesh& mesh) {
  std::unordered_map<uint64_t, int32_t> undirected;
  for (const auto& f : mesh.faces)
    for (int k = 0; k < 3; ++k) {
      const int32_t a = f[k], b = f[(k + 1) % 3];
      ++undirected[Key(std::min(a, b), std::max(a, b))];
    }
  if (mesh.faces.empty()) return false;
  for (const auto& [k, n] : undirected)
    if (n != 2) return false;
  return true;
}

}  // namespace silk
