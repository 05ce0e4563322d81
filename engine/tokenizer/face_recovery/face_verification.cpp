// Replays the encoder's layering on a candidate face set; see face_verification.h.
#include "tokenizer/face_recovery/face_verification.h"

#include <algorithm>
#include <numeric>

namespace silk {
namespace {

// How many of a layer's latest contributors a run defect also suspects (a run that stopped
// short shows up at the next contributor).
constexpr size_t kRecentContributors = 2;

struct Corner {
  int32_t a, b;     // (v, a, b) is the face's winding rotated to start at v
  int32_t rank;     // position of the face's sort-key class (equal keys share a rank)
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

}  // namespace

FaceVerification VerifyComponentFaces(const ComponentGraph& g, const std::vector<std::array<int32_t, 3>>& faces) {
  FaceVerification res;
  const int32_t nv = g.vertex_count;
  const int32_t layer_count = static_cast<int32_t>(g.layer_start.size()) - 1;
  // §4.1: faces by (Σy, Σz, Σx); ties share a rank.
  auto key = [&](const std::array<int32_t, 3>& f) {
    std::array<int32_t, 3> k{0, 0, 0};
    for (int32_t v : f) {
      const QVec& q = g.positions[static_cast<size_t>(v)];
      k[0] += q.y;
      k[1] += q.z;
      k[2] += q.x;
    }
    return k;
  };
  std::vector<std::array<int32_t, 3>> keys(faces.size());
  for (size_t i = 0; i < faces.size(); ++i) keys[i] = key(faces[i]);
  std::vector<int32_t> order(faces.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int32_t a, int32_t b) { return keys[a] < keys[b]; });
  std::vector<int32_t> corner_begin(static_cast<size_t>(nv) + 1, 0);
  for (const auto& f : faces)
    for (int32_t v : f) ++corner_begin[static_cast<size_t>(v) + 1];
  for (int32_t v = 0; v < nv; ++v) corner_begin[v + 1] += corner_begin[v];
  std::vector<Corner> corners(static_cast<size_t>(corner_begin[nv]));
  std::vector<int32_t> fill(corner_begin.begin(), corner_begin.end() - 1);
  int32_t rank = -1;
  for (size_t r = 0; r < order.size(); ++r) {
    const int32_t i = order[r];
    if (r == 0 || keys[order[r - 1]] != keys[i]) rank = static_cast<int32_t>(r);
    const auto& f = faces[static_cast<size_t>(i)];
    for (int k = 0; k < 3; ++k)
      corners[static_cast<size_t>(fill[f[k]]++)] = {f[(k + 1) % 3], f[(k + 2) % 3], rank};
  }
  std::vector<char> flagged(static_cast<size_t>(nv), 0);
  auto flag = [&](int32_t v) {
    if (v >= 0 && !flagged[static_cast<size_t>(v)]) {
      flagged[static_cast<size_t>(v)] = 1;
      res.suspects.push_back(v);
    }
  };
  auto flag_prev_neighbours = [&](int32_t x, int32_t layer) {
    if (x < 0) return;
    for (int32_t w : g.neighbors[static_cast<size_t>(x)])
      if (g.layer_of[static_cast<size_t>(w)] == layer) flag(w);
  };
  // §4.4: the root is the smallest (y, z, x) corner of a first face.
  if (!order.empty()) {
    bool root_ok = false;
    for (size_t r = 0; r < order.size() && keys[order[r]] == keys[order[0]]; ++r) {
      const auto& f = faces[static_cast<size_t>(order[r])];
      int32_t best = f[0];
      for (int k = 1; k < 3; ++k)
        if (LessYZX(g.positions[static_cast<size_t>(f[k])], g.positions[static_cast<size_t>(best)])) best = f[k];
      root_ok = root_ok || best == 0;
    }
    if (!root_ok) {  // a face sorts before the root's faces, or the root's faces are wrong
      ++res.bad_runs;
      res.first_defect = 0;
      flag(0);
      for (int32_t v : faces[static_cast<size_t>(order[0])]) flag(v);
    }
  }
  // §5.3 replayed per layer with the decoded earlier layers as the visited set.
  std::vector<char> collected(static_cast<size_t>(nv), 0);
  std::vector<Corner> cs;
  std::vector<int32_t> rot, starts, run, best_run;
  std::vector<std::pair<int32_t, int32_t>> next;
  for (int32_t L = 1; L < layer_count; ++L) {
    const int32_t begin = g.layer_start[L], end = g.layer_start[L + 1];
    int32_t pos = begin;
    std::vector<int32_t> contribs;  // layer L-1 vertices that added to layer L, in order
    for (int32_t u = g.layer_start[L - 1]; u < g.layer_start[L]; ++u) {
      // An edge of u to the expected layer-L vertex that lies in no 3-cycle is in no face,
      // yet the encoder's run put its end here (its face was unencodable, §5.4). No face
      // set can produce it: count it (not a search target: not flagged, not first_defect)
      // and collect it as the tokens say, so the later runs of this layer stay aligned.
      if (pos < end) {
        const int32_t e = g.EdgeOf(u, pos);
        if (e >= 0 && g.edge_triangles[static_cast<size_t>(e)].empty()) {
          ++res.bad_runs;
          collected[static_cast<size_t>(pos)] = 1;
          while (pos < end && collected[static_cast<size_t>(pos)]) ++pos;
        }
      }
      cs.assign(corners.begin() + corner_begin[u], corners.begin() + corner_begin[u + 1]);
      bool ok = !cs.empty() && RotationOf(cs, &rot, &starts, &next);
      bool matched = false;
      int32_t miss_run = -1, miss_expected = -1;
      best_run.clear();
      if (ok) {
        for (size_t si = 0; si < starts.size() && !matched; ++si) {
          RunOf(g, rot, starts[si], L, &run);
          if (si == 0) best_run = run;
          // New elements must continue the decoded layer in order.
          int32_t p = pos;
          bool good = true;
          for (int32_t x : run) {
            if (g.layer_of[static_cast<size_t>(x)] != L) { good = false; }
            else if (collected[static_cast<size_t>(x)]) continue;
            else if (x != p) { good = false; }
            if (!good) {
              if (si == 0) {
                miss_run = x;
                miss_expected = p < end ? p : -1;
              }
              break;
            }
            ++p;
            while (p < end && collected[static_cast<size_t>(p)]) ++p;
          }
          if (good) {
            matched = true;
            best_run = run;
          }
        }
      }
      if (!matched) {
        ++res.bad_runs;
        res.first_defect = std::min(res.first_defect, u);
        flag(u);
        for (size_t k = contribs.size(); k-- > 0 && contribs.size() - k <= kRecentContributors;) flag(contribs[k]);
        flag_prev_neighbours(miss_expected, L - 1);
        flag_prev_neighbours(miss_run, L - 1);
      }
      bool contributed = false;
      for (int32_t x : best_run) {
        if (g.layer_of[static_cast<size_t>(x)] != L || collected[static_cast<size_t>(x)]) continue;
        collected[static_cast<size_t>(x)] = 1;
        contributed = true;
      }
      while (pos < end && collected[static_cast<size_t>(pos)]) ++pos;
      if (contributed) contribs.push_back(u);
    }
    if (pos < end) {
      ++res.bad_runs;
      res.first_defect = std::min(res.first_defect, g.layer_start[L] - 1);
      for (size_t k = contribs.size(); k-- > 0 && contribs.size() - k <= kRecentContributors;) flag(contribs[k]);
      flag_prev_neighbours(pos, L - 1);
    }
  }
  // The last layer has no run to replay, but its vertices must still have one fan each (the
  // encoder splits a vertex with two fans, §3): a detached fan there is a defect too.
  if (layer_count >= 1) {
    for (int32_t u = g.layer_start[layer_count - 1]; u < g.layer_start[layer_count]; ++u) {
      cs.assign(corners.begin() + corner_begin[u], corners.begin() + corner_begin[u + 1]);
      if (cs.empty() || RotationOf(cs, &rot, &starts, &next)) continue;
      ++res.bad_runs;
      res.first_defect = std::min(res.first_defect, u);
      flag(u);
    }
  }
  // Every decoded edge is an edge of some face.
  std::vector<char> covered(g.edges.size(), 0);
  for (const auto& f : faces)
    for (int k = 0; k < 3; ++k) {
      const int32_t e = g.EdgeOf(f[k], f[(k + 1) % 3]);
      if (e >= 0) covered[static_cast<size_t>(e)] = 1;
    }
  for (size_t e = 0; e < g.edges.size(); ++e) {
    if (covered[e]) continue;
    ++res.uncovered_edges;
    res.first_defect = std::min(res.first_defect, g.vertex_count + g.edges[e][0]);
    flag(g.edges[e][0]);
    flag(g.edges[e][1]);
  }
  return res;
}

}  // namespace silk
