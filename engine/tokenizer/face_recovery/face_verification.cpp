// SPDX-License-Identifier: MIT
// Replays the encoder's layering on a candidate face set; see face_verification.h.
#include "tokenizer/face_recovery/face_verification.h"

#include <algorithm>
#include <numeric>
#include <utility>

namespace silk {
namespace {

// How many of a layer's latest contributors a run defect also suspects (a run that stopped
// short shows up at the next contributor).
constexpr size_t kRecentContributors = 2;

struct Corner {
  int32_t a, b;  // (v, a, b) is the face's winding rotated to start at v
  int32_t rank;  // position of the face's sort-key class (equal keys share a rank)
};

// R(v) of one vertex from its corners in sorted face order, plus the interior start options.
// Returns false where the encoder would refuse or the fan is not one cycle/path.
bool RotationOf(const std::vector<Corner>& cs, std::vector<int32_t>* rot, std::vector<int32_t>* starts,
                std::vector<std::pair<int32_t, int32_t>>* next) {
  rot->clear();
  starts->clear();
  next->clear();
  for (const Corner& c : cs) next->push_back({c.a, c.b});
  std::sort(next->begin(), next->end());
  for (size_t i = 1; i < next->size(); ++i)
    if ((*next)[i].first == (*next)[i - 1].first) return false;  // a directed edge used twice
  std::vector<int32_t> bs;
  for (const Corner& c : cs) bs.push_back(c.b);
  std::sort(bs.begin(), bs.end());
  int32_t n_starts = 0, start = -1;
  for (const Corner& c : cs) {  // sorted face order: the first boundary a_f
    if (!std::binary_search(bs.begin(), bs.end(), c.a)) {
      if (n_starts++ == 0) start = c.a;
    }
  }
  if (n_starts > 1) return false;
  auto next_of = [&](int32_t a, int32_t* b) {
    auto it = std::lower_bound(next->begin(), next->end(), std::make_pair(a, INT32_MIN));
    if (it == next->end() || it->first != a) return false;
    *b = it->second;
    return true;
  };
  const size_t n = cs.size();
  if (n_starts == 1) {
    int32_t cur = start, nx;
    rot->push_back(cur);
    for (size_t guard = 0; guard < n && next_of(cur, &nx); ++guard) {
      rot->push_back(nx);
      cur = nx;
    }
    if (rot->size() != n + 1) return false;  // a detached cycle besides the path
    starts->push_back(0);
    return true;
  }
  int32_t cur = cs.front().a, nx;
  rot->push_back(cur);
  for (size_t guard = 0; guard + 1 < n && next_of(cur, &nx) && nx != cs.front().a; ++guard) {
    rot->push_back(nx);
    cur = nx;
  }
  if (rot->size() != n) return false;  // two fans at one vertex
  // Tied first faces: each one's a_f may be the start (processed face order is unknown).
  for (const Corner& c : cs) {
    if (c.rank != cs.front().rank) break;
    const auto it = std::find(rot->begin(), rot->end(), c.a);
    starts->push_back(static_cast<int32_t>(it - rot->begin()));
  }
  return true;
}

// §5.2 on R rotated to start at `s`; visited = layer < L.
void RunOf(const ComponentGraph& g, const std::vector<int32_t>& rot, int32_t s, int32_t L, std::vector<int32_t>* out) {
  out->clear();
  const int32_t n = static_cast<int32_t>(rot.size());
  auto at = [&](int32_t k) { return rot[static_cast<size_t>((s + k) % n)]; };
  auto visited = [&](int32_t x) { return g.layer_of[static_cast<size_t>(x)] < L; };
  int32_t i0 = -1;
  bool any_unvisited = false;
  for (int32_t k = 0; k < n; ++k) {
    if (visited(at(k))) {
      if (i0 < 0) i0 = k;
    } else {
      any_unvisited = true;
    }
  }
  if (!any_unvisited) return;
  if (i0 < 0) {
    for (int32_t k = 0; k < n; ++k) out->push_back(at(k));
    return;
  }
  for (int32_t k = 1; k < n; ++k) {
    const int32_t x = at((i0 + k) % n);
    if (visited(x)) {
      if (!out->empty()) break;
      continue;
    }
    out->push_back(x);
  }
}

using Face = std::array<int32_t, 3>;

// The candidate faces' corners grouped by vertex, each vertex's corners in sorted face order.
struct SortedCorners {
  std::vector<std::array<int32_t, 3>> keys;  // per face: (Σy, Σz, Σx)
  std::vector<int32_t> order;                // face indices by key (stable)
  std::vector<int32_t> begin;                // per vertex (+ end): first corner of the vertex
  std::vector<Corner> corners;
};

// §4.1: faces by (Σy, Σz, Σx); ties share a rank.
SortedCorners SortCorners(const ComponentGraph& g, const std::vector<Face>& faces) {
  SortedCorners sc;
  const int32_t nv = g.vertex_count;
  auto key = [&](const Face& f) {
    std::array<int32_t, 3> k{0, 0, 0};
    for (int32_t v : f) {
      const QVec& q = g.positions[static_cast<size_t>(v)];
      k[0] += q.y;
      k[1] += q.z;
      k[2] += q.x;
    }
    return k;
  };
  sc.keys.resize(faces.size());
  for (size_t i = 0; i < faces.size(); ++i) sc.keys[i] = key(faces[i]);
  sc.order.resize(faces.size());
  std::iota(sc.order.begin(), sc.order.end(), 0);
  const auto& keys = sc.keys;
  std::stable_sort(sc.order.begin(), sc.order.end(), [&](int32_t a, int32_t b) { return keys[a] < keys[b]; });
  sc.begin.assign(static_cast<size_t>(nv) + 1, 0);
  for (const auto& f : faces)
    for (int32_t v : f) ++sc.begin[static_cast<size_t>(v) + 1];
  for (int32_t v = 0; v < nv; ++v) sc.begin[v + 1] += sc.begin[v];
  sc.corners.resize(static_cast<size_t>(sc.begin[nv]));
  std::vector<int32_t> fill(sc.begin.begin(), sc.begin.end() - 1);
  int32_t rank = -1;
  for (size_t r = 0; r < sc.order.size(); ++r) {
    const int32_t i = sc.order[r];
    if (r == 0 || keys[sc.order[r - 1]] != keys[i]) rank = static_cast<int32_t>(r);
    const auto& f = faces[static_cast<size_t>(i)];
    for (int k = 0; k < 3; ++k) sc.corners[static_cast<size_t>(fill[f[k]]++)] = {f[(k + 1) % 3], f[(k + 2) % 3], rank};
  }
  return sc;
}

// One verification of a face set: the replay's state, the defect tally and the suspects.
class FaceReplay {
 public:
  FaceReplay(const ComponentGraph& g, const std::vector<Face>& faces)
      : g_(g),
        faces_(faces),
        sc_(SortCorners(g, faces)),
        flagged_(static_cast<size_t>(g.vertex_count), 0),
        collected_(static_cast<size_t>(g.vertex_count), 0) {}

  FaceVerification Run() {
    const int32_t layer_count = static_cast<int32_t>(g_.layer_start.size()) - 1;
    CheckRoot();
    // §5.3 replayed per layer with the decoded earlier layers as the visited set.
    for (int32_t L = 1; L < layer_count; ++L) ReplayLayer(L);
    CheckLastLayerFans(layer_count);
    CheckEdgeCoverage();
    return std::move(res_);
  }

 private:
  void Flag(int32_t v) {
    if (v >= 0 && !flagged_[static_cast<size_t>(v)]) {
      flagged_[static_cast<size_t>(v)] = 1;
      res_.suspects.push_back(v);
    }
  }
  void FlagPrevNeighbours(int32_t x, int32_t layer) {
    if (x < 0) return;
    for (int32_t w : g_.neighbors[static_cast<size_t>(x)])
      if (g_.layer_of[static_cast<size_t>(w)] == layer) Flag(w);
  }
  void FlagRecentContributors(const std::vector<int32_t>& contribs) {
    for (size_t k = contribs.size(); k-- > 0 && contribs.size() - k <= kRecentContributors;) Flag(contribs[k]);
  }
  // cs_ = the corners of u in sorted face order.
  void LoadCorners(int32_t u) {
    cs_.assign(sc_.corners.begin() + sc_.begin[u], sc_.corners.begin() + sc_.begin[u + 1]);
  }

  // §4.4: the root is the smallest (y, z, x) corner of a first face.
  void CheckRoot() {
    const auto& order = sc_.order;
    const auto& keys = sc_.keys;
    if (order.empty()) return;
    bool root_ok = false;
    for (size_t r = 0; r < order.size() && keys[order[r]] == keys[order[0]]; ++r) {
      const auto& f = faces_[static_cast<size_t>(order[r])];
      int32_t best = f[0];
      for (int k = 1; k < 3; ++k)
        if (LessYZX(g_.positions[static_cast<size_t>(f[k])], g_.positions[static_cast<size_t>(best)])) best = f[k];
      root_ok = root_ok || best == 0;
    }
    if (!root_ok) {  // a face sorts before the root's faces, or the root's faces are wrong
      ++res_.bad_runs;
      res_.first_defect = 0;
      Flag(0);
      for (int32_t v : faces_[static_cast<size_t>(order[0])]) Flag(v);
    }
  }

  // The runs of layer L-1's vertices against decoded layer L.
  void ReplayLayer(int32_t L) {
    const int32_t end = g_.layer_start[L + 1];
    int32_t pos = g_.layer_start[L];
    std::vector<int32_t> contribs;  // layer L-1 vertices that added to layer L, in order
    for (int32_t u = g_.layer_start[L - 1]; u < g_.layer_start[L]; ++u) {
      SkipFacelessEdge(u, end, &pos);
      int32_t miss_run = -1, miss_expected = -1;
      if (!MatchRun(u, L, pos, end, &miss_run, &miss_expected)) {
        ++res_.bad_runs;
        res_.first_defect = std::min(res_.first_defect, u);
        Flag(u);
        FlagRecentContributors(contribs);
        FlagPrevNeighbours(miss_expected, L - 1);
        FlagPrevNeighbours(miss_run, L - 1);
      }
      const bool contributed = CollectBestRun(L);
      while (pos < end && collected_[static_cast<size_t>(pos)]) ++pos;
      if (contributed) contribs.push_back(u);
    }
    if (pos < end) {
      ++res_.bad_runs;
      res_.first_defect = std::min(res_.first_defect, g_.layer_start[L] - 1);
      FlagRecentContributors(contribs);
      FlagPrevNeighbours(pos, L - 1);
    }
  }

  // An edge of u to the expected layer-L vertex that lies in no 3-cycle is in no face,
  // yet the encoder's run put its end here (its face was unencodable, §5.4). No face
  // set can produce it: count it (not a search target: not flagged, not first_defect)
  // and collect it as the tokens say, so the later runs of this layer stay aligned.
  void SkipFacelessEdge(int32_t u, int32_t end, int32_t* pos) {
    if (*pos >= end) return;
    const int32_t e = g_.EdgeOf(u, *pos);
    if (e >= 0 && g_.edge_triangles[static_cast<size_t>(e)].empty()) {
      ++res_.bad_runs;
      collected_[static_cast<size_t>(*pos)] = 1;
      while (*pos < end && collected_[static_cast<size_t>(*pos)]) ++*pos;
    }
  }

  // Tries each start option of u's rotation list; true if one run continues layer L at `pos`.
  // best_run_ is then that run, else the first start's run (empty without a valid fan); the
  // first start's mismatch names the run vertex that broke it and the vertex expected there.
  bool MatchRun(int32_t u, int32_t L, int32_t pos, int32_t end, int32_t* miss_run, int32_t* miss_expected) {
    best_run_.clear();
    LoadCorners(u);
    if (cs_.empty() || !RotationOf(cs_, &rot_, &starts_, &next_)) return false;
    for (size_t si = 0; si < starts_.size(); ++si) {
      RunOf(g_, rot_, starts_[si], L, &run_);
      if (si == 0) best_run_ = run_;
      int32_t bad_x = -1, expected = -1;
      if (ContinuesLayer(L, pos, end, &bad_x, &expected)) {
        best_run_ = run_;
        return true;
      }
      if (si == 0) {
        *miss_run = bad_x;
        *miss_expected = expected;
      }
    }
    return false;
  }

  // New elements of run_ must continue the decoded layer L in order from `pos`. On a
  // mismatch: the run vertex that broke it and the layer vertex expected there (-1: none).
  bool ContinuesLayer(int32_t L, int32_t pos, int32_t end, int32_t* bad_x, int32_t* expected) const {
    int32_t p = pos;
    for (int32_t x : run_) {
      const bool in_layer = g_.layer_of[static_cast<size_t>(x)] == L;
      if (in_layer && collected_[static_cast<size_t>(x)]) continue;
      if (!in_layer || x != p) {
        *bad_x = x;
        *expected = p < end ? p : -1;
        return false;
      }
      ++p;
      while (p < end && collected_[static_cast<size_t>(p)]) ++p;
    }
    return true;
  }

  // Collects best_run_'s new layer-L vertices; true if there was one.
  bool CollectBestRun(int32_t L) {
    bool contributed = false;
    for (int32_t x : best_run_) {
      if (g_.layer_of[static_cast<size_t>(x)] != L || collected_[static_cast<size_t>(x)]) continue;
      collected_[static_cast<size_t>(x)] = 1;
      contributed = true;
    }
    return contributed;
  }

  // The last layer has no run to replay, but its vertices must still have one fan each (the
  // encoder splits a vertex with two fans, §3): a detached fan there is a defect too.
  void CheckLastLayerFans(int32_t layer_count) {
    if (layer_count < 1) return;
    for (int32_t u = g_.layer_start[layer_count - 1]; u < g_.layer_start[layer_count]; ++u) {
      LoadCorners(u);
      if (cs_.empty() || RotationOf(cs_, &rot_, &starts_, &next_)) continue;
      ++res_.bad_runs;
      res_.first_defect = std::min(res_.first_defect, u);
      Flag(u);
    }
  }

  // Every decoded edge is an edge of some face.
  void CheckEdgeCoverage() {
    std::vector<char> covered(g_.edges.size(), 0);
    for (const auto& f : faces_)
      for (int k = 0; k < 3; ++k) {
        const int32_t e = g_.EdgeOf(f[k], f[(k + 1) % 3]);
        if (e >= 0) covered[static_cast<size_t>(e)] = 1;
      }
    for (size_t e = 0; e < g_.edges.size(); ++e) {
      if (covered[e]) continue;
      ++res_.uncovered_edges;
      res_.first_defect = std::min(res_.first_defect, g_.vertex_count + g_.edges[e][0]);
      Flag(g_.edges[e][0]);
      Flag(g_.edges[e][1]);
    }
  }

  const ComponentGraph& g_;
  const std::vector<Face>& faces_;
  const SortedCorners sc_;
  FaceVerification res_;
  std::vector<char> flagged_;
  std::vector<char> collected_;  // layer vertices the replayed runs have reached
  // Scratch reused across vertices.
  std::vector<Corner> cs_;
  std::vector<int32_t> rot_, starts_, run_, best_run_;
  std::vector<std::pair<int32_t, int32_t>> next_;
};

}  // namespace

FaceVerification VerifyComponentFaces(const ComponentGraph& g, const std::vector<std::array<int32_t, 3>>& faces) {
  return FaceReplay(g, faces).Run();
}

}  // namespace silk
