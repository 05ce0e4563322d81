// SPDX-License-Identifier: MIT
// Non-manifold processing (token_format.md §3.3-§3.6): passes A, B and C of the reference, splitting
// vertices into copies. Plain fans take a fast path; only true non-manifold fans reach the
// order emulation.
#include "tokenizer/manifold/nonmanifold_split.h"

#include <array>
#include <string>
#include <vector>

#include "tokenizer/manifold/nonmanifold_partition.h"
#include "tokenizer/manifold/reference_order_emulation.h"
#include "tokenizer/refusal.h"
#include "tokenizer/manifold/union_find.h"
#include "tokenizer/manifold/vertex_edge_graph.h"

namespace silk {
namespace {

constexpr size_t kMaxIncidentList = 50;        // NM_max_edge_graph
constexpr int32_t kMaxNonManifoldVerts = 300;  // NM_max_nonmani_verts

using RawFace = std::array<int32_t, 3>;

// Faces containing each vertex, ascending face index (flat arrays).
struct Incidence {
  std::vector<int32_t> start;  // size n + 1
  std::vector<int32_t> faces;
  const int32_t* begin(int32_t v) const { return faces.data() + start[static_cast<size_t>(v)]; }
  size_t count(int32_t v) const {
    return static_cast<size_t>(start[static_cast<size_t>(v) + 1] - start[static_cast<size_t>(v)]);
  }
};

Incidence BuildIncidence(const std::vector<RawFace>& faces, int32_t n) {
  Incidence inc;
  inc.start.assign(static_cast<size_t>(n) + 1, 0);
  for (const auto& f : faces)
    for (int32_t c : f) ++inc.start[static_cast<size_t>(c) + 1];
  for (size_t i = 0; i < static_cast<size_t>(n); ++i) inc.start[i + 1] += inc.start[i];
  inc.faces.resize(faces.size() * 3);
  std::vector<int32_t> fill(inc.start.begin(), inc.start.end() - 1);
  for (size_t fi = 0; fi < faces.size(); ++fi)
    for (int32_t c : faces[fi])
      inc.faces[static_cast<size_t>(fill[static_cast<size_t>(c)]++)] = static_cast<int32_t>(fi);
  return inc;
}

struct SplitState {
  std::vector<RawFace> faces;
  std::vector<QVec> positions;
  int32_t copies = 0;
};

// split(v, groups) (token_format.md §3.6): group 0 keeps v, group k gets a new copy. Returns the corners
// other than v of the faces of groups 1.. (the reference's `infl`, before set()).
std::vector<int32_t> SplitVertex(SplitState& s, int32_t v, const std::vector<std::vector<FaceId>>& groups) {
  std::vector<int32_t> infl;
  for (size_t k = 1; k < groups.size(); ++k) {
    const int32_t copy = static_cast<int32_t>(s.positions.size());
    s.positions.push_back(s.positions[static_cast<size_t>(v)]);
    ++s.copies;
    for (FaceId f : groups[k]) {
      for (int32_t& c : s.faces[static_cast<size_t>(f.get())]) {
        if (c == v)
          c = copy;
        else
          infl.push_back(c);
      }
    }
  }
  return infl;
}

// Groups of a disconnected fan in passes A and C: components in networkx order, faces in
// `edges(component)` order.
std::vector<std::vector<FaceId>> ComponentGroups(const VertexEdgeGraph& eg) {
  const refemu::NxGraph g = refemu::NxFromEdges(eg.keys);
  std::vector<std::vector<FaceId>> groups;
  for (const auto& comp : refemu::NxConnectedComponents(g)) {
    std::vector<FaceId> grp;
    for (const auto& e : refemu::NxEdges(g, comp))
      grp.emplace_back(eg.FaceOf(g.label[static_cast<size_t>(e.first)], g.label[static_cast<size_t>(e.second)]));
    groups.push_back(std::move(grp));
  }
  return groups;
}

// Pass A (token_format.md §3.3). Records each split vertex's group as its pass-A list.
void PassA(SplitState& s, std::vector<std::vector<int32_t>>* pass_a_list) {
  const std::vector<RawFace> snapshot = s.faces;  // stale graphs: built from the start state
  const int32_t n = static_cast<int32_t>(s.positions.size());
  const Incidence inc = BuildIncidence(snapshot, n);
  for (int32_t v = 0; v < n; ++v) {
    if (inc.count(v) == 0) continue;
    const VertexEdgeGraph eg = BuildVertexEdgeGraph(snapshot, v, inc.begin(v), inc.count(v));
    if (InspectEdgeGraph(eg.keys).components <= 1) continue;
    const auto groups = ComponentGroups(eg);
    const int32_t first_copy = static_cast<int32_t>(s.positions.size());
    SplitVertex(s, v, groups);
    pass_a_list->resize(s.positions.size());
    for (size_t k = 0; k < groups.size(); ++k) {
      auto& dst = (*pass_a_list)[static_cast<size_t>(k == 0 ? v : first_copy + static_cast<int32_t>(k) - 1)];
      dst.clear();
      for (FaceId f : groups[k]) dst.push_back(f.get());
    }
  }
  pass_a_list->resize(s.positions.size());
}

// Pass B step 1 (token_format.md §3.4): each vertex's list_v (its pass-A list, then its faces)
// and the shape of its fan.
struct FanSurvey {
  std::vector<std::vector<int32_t>> lists;  // list_v per vertex
  std::vector<char> manifold;               // the fan is one path or cycle
  std::vector<int32_t> nm_verts;            // non-manifold vertices, ascending
  std::vector<int32_t> nm_cycle_verts;      // those whose fan has a cycle
};

Status SurveyFans(const SplitState& s, const std::vector<std::vector<int32_t>>& pass_a_list, FanSurvey* fs) {
  const int32_t n = static_cast<int32_t>(s.positions.size());
  const Incidence inc = BuildIncidence(s.faces, n);
  fs->lists.resize(static_cast<size_t>(n));
  fs->manifold.assign(static_cast<size_t>(n), 0);
  for (int32_t v = 0; v < n; ++v) {
    auto& list = fs->lists[static_cast<size_t>(v)];
    list = pass_a_list[static_cast<size_t>(v)];
    list.insert(list.end(), inc.begin(v), inc.begin(v) + inc.count(v));
    if (list.empty()) continue;
    if (list.size() > kMaxIncidentList)
      return Refuse(Refusal::kEdgeGraphLimit, std::to_string(list.size()) + " > 50 at vertex " + std::to_string(v));
    const VertexEdgeGraph eg = BuildVertexEdgeGraph(s.faces, v, list.data(), list.size());
    const EdgeGraphShape shape = InspectEdgeGraph(eg.keys);
    if (shape.components != 1) return Refuse(Refusal::kStillDisconnectedFan, "vertex " + std::to_string(v));
    if (shape.max_degree_le2) {
      fs->manifold[static_cast<size_t>(v)] = 1;
      continue;
    }
    fs->nm_verts.push_back(v);
    if (static_cast<int32_t>(eg.keys.size()) >= shape.nodes) fs->nm_cycle_verts.push_back(v);
  }
  return Status::Ok();
}

// Pass B face components (SELECT_CYCLE rule 1): manifold vertices joined through shared faces
// (pre-components); a face's component comes from any manifold corner, -1 without one.
struct FaceComponents {
  UnionFind uf;
  std::vector<int32_t> face_cc;  // per face
};

FaceComponents ManifoldFaceComponents(const SplitState& s, const std::vector<char>& manifold) {
  const int32_t n = static_cast<int32_t>(s.positions.size());
  UnionFind pre(n);
  for (const auto& f : s.faces) {
    int32_t first = -1;
    for (int32_t c : f) {
      if (!manifold[static_cast<size_t>(c)]) continue;
      if (first < 0)
        first = c;
      else
        pre.Union(first, c);
    }
  }
  std::vector<int32_t> comp_id(static_cast<size_t>(n), -1);
  int32_t ids = 0;
  for (int32_t v = 0; v < n; ++v) {
    if (!manifold[static_cast<size_t>(v)]) continue;
    const int32_t r = pre.Find(v);
    if (comp_id[static_cast<size_t>(r)] < 0) comp_id[static_cast<size_t>(r)] = ids++;
  }
  FaceComponents fc{UnionFind(ids), std::vector<int32_t>(s.faces.size(), -1)};
  for (size_t fi = 0; fi < s.faces.size(); ++fi)
    for (int32_t c : s.faces[fi])
      if (manifold[static_cast<size_t>(c)]) {
        fc.face_cc[fi] = comp_id[static_cast<size_t>(pre.Find(c))];
        break;
      }
  return fc;
}

// Joins the face components each group touches; per group the joined root, -1 for none.
std::vector<int32_t> JoinGroupComponents(const std::vector<std::vector<FaceId>>& groups, FaceComponents& fc) {
  std::vector<int32_t> roots;
  for (const auto& grp : groups) {
    std::vector<int32_t> cc;
    for (FaceId f : grp)
      if (fc.face_cc[static_cast<size_t>(f.get())] != -1) cc.push_back(fc.face_cc[static_cast<size_t>(f.get())]);
    if (cc.empty()) {
      roots.push_back(-1);
      continue;
    }
    for (size_t i = 0; i + 1 < cc.size(); ++i) fc.uf.Union(cc[i], cc[i + 1]);
    roots.push_back(fc.uf.Find(cc[0]));
  }
  return roots;
}

// Gives each group's faces without a component the group's root, or a fresh component.
void AssignGroupComponents(const std::vector<std::vector<FaceId>>& groups, const std::vector<int32_t>& roots,
                           FaceComponents& fc) {
  for (size_t k = 0; k < groups.size(); ++k) {
    if (roots[k] == -1) {
      const int32_t fresh = fc.uf.Extend();
      for (FaceId f : groups[k]) fc.face_cc[static_cast<size_t>(f.get())] = fresh;
    } else {
      for (FaceId f : groups[k])
        if (fc.face_cc[static_cast<size_t>(f.get())] == -1) fc.face_cc[static_cast<size_t>(f.get())] = roots[k];
    }
  }
}

// NM_process_one: splits one non-manifold vertex by PARTITION(v) and updates the face
// components; pushes the influenced neighbours onto `queue` in the reference's set order.
Status ProcessNonManifoldVertex(SplitState& s, int32_t v, const std::vector<int32_t>& list, FaceComponents& fc,
                                std::vector<int32_t>* queue) {
  std::vector<std::vector<FaceId>> groups;
  SILK_RETURN_IF_ERROR(PartitionNonManifoldFan(s.faces, v, list, fc.face_cc, fc.uf, &groups));
  const std::vector<int32_t> roots = JoinGroupComponents(groups, fc);
  for (int32_t x : refemu::PySetOrderInts(SplitVertex(s, v, groups))) queue->push_back(x);
  AssignGroupComponents(groups, roots, fc);
  return Status::Ok();
}

// The order pass B processes non-manifold vertices in: the latest influenced neighbour still
// pending (the reference's LIFO `queue`), else the first pending one.
class NonManifoldOrder {
 public:
  NonManifoldOrder(int32_t n, const std::vector<int32_t>& nm_verts)
      : nm_verts_(nm_verts), pending_(static_cast<size_t>(n), 0), processed_(static_cast<size_t>(n), 0) {
    for (int32_t v : nm_verts) pending_[static_cast<size_t>(v)] = 1;
  }
  std::vector<int32_t>* queue() { return &queue_; }
  void MarkProcessed(int32_t v) { processed_[static_cast<size_t>(v)] = 1; }
  void MarkDone(int32_t v) { pending_[static_cast<size_t>(v)] = 0; }
  // Only while some vertex is still pending.
  int32_t Next() {
    const int32_t n = static_cast<int32_t>(pending_.size());
    while (!queue_.empty()) {
      const int32_t x = queue_.back();
      queue_.pop_back();
      if (x < n && !processed_[static_cast<size_t>(x)] && pending_[static_cast<size_t>(x)]) return x;
    }
    while (!pending_[static_cast<size_t>(nm_verts_[pending_scan_])]) ++pending_scan_;
    return nm_verts_[pending_scan_];
  }

 private:
  const std::vector<int32_t>& nm_verts_;
  std::vector<char> pending_, processed_;
  size_t pending_scan_ = 0;
  std::vector<int32_t> queue_;
};

// Pass B (token_format.md §3.4).
Status PassB(SplitState& s, const std::vector<std::vector<int32_t>>& pass_a_list, int32_t* nm_count) {
  const int32_t n = static_cast<int32_t>(s.positions.size());
  FanSurvey fs;
  SILK_RETURN_IF_ERROR(SurveyFans(s, pass_a_list, &fs));
  *nm_count = static_cast<int32_t>(fs.nm_verts.size());
  if (fs.nm_verts.size() > static_cast<size_t>(kMaxNonManifoldVerts))
    return Refuse(Refusal::kTooManyNonManifoldVerts, std::to_string(fs.nm_verts.size()) + " > 300");
  if (fs.nm_verts.empty()) return Status::Ok();

  FaceComponents fc = ManifoldFaceComponents(s, fs.manifold);
  // Sequential processing, starting from the first vertex whose fan has a cycle.
  NonManifoldOrder order(n, fs.nm_verts);
  size_t remaining = fs.nm_verts.size();
  int32_t cur = fs.nm_cycle_verts.empty() ? fs.nm_verts.front() : fs.nm_cycle_verts.front();
  while (true) {
    order.MarkProcessed(cur);
    SILK_RETURN_IF_ERROR(ProcessNonManifoldVertex(s, cur, fs.lists[static_cast<size_t>(cur)], fc, order.queue()));
    order.MarkDone(cur);
    if (--remaining == 0) break;
    cur = order.Next();
  }
  return Status::Ok();
}

// Pass C (token_format.md §3.5).
Status PassC(SplitState& s) {
  const std::vector<RawFace> snapshot = s.faces;
  const int32_t n = static_cast<int32_t>(s.positions.size());
  const Incidence inc = BuildIncidence(snapshot, n);
  for (int32_t v = 0; v < n; ++v) {
    if (inc.count(v) == 0) continue;
    const VertexEdgeGraph eg = BuildVertexEdgeGraph(snapshot, v, inc.begin(v), inc.count(v));
    const EdgeGraphShape shape = InspectEdgeGraph(eg.keys);
    if (shape.component_with_extra_edge) return Refuse(Refusal::kPostNotManifold, "vertex " + std::to_string(v));
    if (shape.components <= 1) continue;
    SplitVertex(s, v, ComponentGroups(eg));
  }
  return Status::Ok();
}

}  // namespace

Status SplitNonManifoldVertices(TokenizerProcessedMesh& mesh, NonManifoldStats* stats) {
  SplitState s;
  s.positions = mesh.positions;
  s.faces.reserve(mesh.faces.size());
  for (const Tri& t : mesh.faces) s.faces.push_back({t[0].get(), t[1].get(), t[2].get()});

  std::vector<std::vector<int32_t>> pass_a_list;
  PassA(s, &pass_a_list);
  int32_t nm_count = 0;
  SILK_RETURN_IF_ERROR(PassB(s, pass_a_list, &nm_count));
  // Without NM vertices pass B changed nothing and found every fan a single path or cycle,
  // which is exactly what pass C would check again.
  if (nm_count > 0) SILK_RETURN_IF_ERROR(PassC(s));

  mesh.positions = std::move(s.positions);
  for (size_t i = 0; i < s.faces.size(); ++i)
    mesh.faces[i] = {VertexId(s.faces[i][0]), VertexId(s.faces[i][1]), VertexId(s.faces[i][2])};
  if (stats) {
    stats->nm_vertices = nm_count;
    stats->copies = s.copies;
  }
  return Status::Ok();
}

}  // namespace silk
