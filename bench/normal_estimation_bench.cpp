// SPDX-License-Identifier: MIT
// Estimated normals against true ones (docs/normals.md): N area-weighted samples of each dev
// mesh with the sampled face's normal, the normals dropped, EstimateNormals for each k, then
// mean |cos| (the normal line) on every mesh, and on the closed meshes (watertight and
// consistently oriented after welding; each component's winding turned outward by the sign of
// its volume) also the share of points whose estimated normal faces outward. Prints one row
// per k plus the time per 10,000 points.
// Usage: normal_estimation_bench [CORPUS_DIR] [--points N] [--k 8,12,16,24] [--noise F]
//        (noise: Gaussian, sigma = F x the bounding-box diagonal)
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <numeric>
#include <string>
#include <vector>

#include "core/splitmix64.h"
#include "io/mesh_reader.h"
#include "mesh/close_vertex_merge.h"
#include "mesh/mesh_checks.h"
#include "mesh/normal_estimation.h"

using namespace silk;
using Clock = std::chrono::steady_clock;

namespace {

struct Sampled {
  std::vector<Point3> points, normals;  // true normals: outward for a closed mesh
  bool closed = false;
};

Point3 Sub(const Point3& a, const Point3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
Point3 Cross(const Point3& a, const Point3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
double Dot(const Point3& a, const Point3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

// +1 / -1 per face: the sign of the volume of the face's connected component.
std::vector<double> ComponentSigns(const IoMesh& m) {
  std::vector<int32_t> parent(m.positions.size());
  std::iota(parent.begin(), parent.end(), 0);
  auto find = [&](int32_t x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  };
  for (const auto& t : m.triangles)
    for (int k = 1; k < 3; ++k) parent[find(t[k])] = find(t[0]);
  std::vector<double> volume(m.positions.size(), 0);
  for (const auto& t : m.triangles)
    volume[find(t[0])] += Dot(m.positions[t[0]], Cross(m.positions[t[1]], m.positions[t[2]]));
  std::vector<double> sign;
  for (const auto& t : m.triangles) sign.push_back(volume[find(t[0])] < 0 ? -1.0 : 1.0);
  return sign;
}

Sampled Sample(const IoMesh& raw, int n, double noise, uint64_t seed) {
  double diag2 = 0;
  Point3 lo = raw.positions[0], hi = lo;
  for (const auto& p : raw.positions)
    for (int a = 0; a < 3; ++a) lo[a] = std::min(lo[a], p[a]), hi[a] = std::max(hi[a], p[a]);
  diag2 = Dot(Sub(hi, lo), Sub(hi, lo));
  const IoMesh m = MergeCloseVertices(raw, 1e-9 * std::sqrt(diag2));
  const MeshVerdicts v = CheckMesh(m);
  Sampled s;
  s.closed = v.watertight && v.consistently_oriented;
  const std::vector<double> sign = ComponentSigns(m);
  std::vector<double> cum;
  double total = 0;
  for (const auto& t : m.triangles) {
    const Point3 c = Cross(Sub(m.positions[t[1]], m.positions[t[0]]), Sub(m.positions[t[2]], m.positions[t[0]]));
    cum.push_back(total += std::sqrt(Dot(c, c)));
  }
  SplitMix64 rng(seed);
  const double sigma = noise * std::sqrt(diag2);
  for (int i = 0; i < n; ++i) {
    const size_t f =
        std::min<size_t>(std::upper_bound(cum.begin(), cum.end(), rng.Uniform() * total) - cum.begin(), cum.size() - 1);
    const auto& t = m.triangles[f];
    double r1 = std::sqrt(rng.Uniform()), r2 = rng.Uniform();
    Point3 p, nrm = Cross(Sub(m.positions[t[1]], m.positions[t[0]]), Sub(m.positions[t[2]], m.positions[t[0]]));
    const double len = std::sqrt(Dot(nrm, nrm));
    for (int a = 0; a < 3; ++a) {
      p[a] = (1 - r1) * m.positions[t[0]][a] + r1 * (1 - r2) * m.positions[t[1]][a] + r1 * r2 * m.positions[t[2]][a];
      if (sigma > 0) {  // Box-Muller
        const double u = std::max(rng.Uniform(), 1e-300), w = rng.Uniform();
        p[a] += sigma * std::sqrt(-2 * std::log(u)) * std::cos(6.283185307179586 * w);
      }
      nrm[a] *= sign[f] / len;
    }
    s.points.push_back(p);
    s.normals.push_back(nrm);
  }
  return s;
}

struct Row {
  double cos_all = 0, cos_closed = 0, outward_closed = 0, seconds = 0;
  int meshes = 0, closed = 0, closed_mostly_right = 0;
  size_t points = 0;
};

void Score(const Sampled& s, const std::vector<Point3>& est, Row* r) {
  double sum_cos = 0, outward = 0;
  for (size_t i = 0; i < est.size(); ++i) {
    const double c = Dot(est[i], s.normals[i]);
    sum_cos += std::fabs(c);
    outward += c > 0 ? 1 : 0;
  }
  const double n = static_cast<double>(est.size());
  r->cos_all += sum_cos / n;
  ++r->meshes;
  if (s.closed) {
    r->cos_closed += sum_cos / n;
    r->outward_closed += outward / n;
    r->closed_mostly_right += outward / n >= 0.9 ? 1 : 0;
    ++r->closed;
  }
}

}  // namespace

int main(int argc, char** argv) {
  std::string dir = "../shared/corpus/dev";
  int n = 10000;
  double noise = 0;
  bool verbose = false;
  std::vector<int> ks{8, 12, 16, 24};
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--verbose")
      verbose = true;
    else if (a == "--points" && i + 1 < argc)
      n = std::atoi(argv[++i]);
    else if (a == "--noise" && i + 1 < argc)
      noise = std::atof(argv[++i]);
    else if (a == "--k" && i + 1 < argc) {
      ks.clear();
      for (char* p = argv[++i]; *p;) ks.push_back(static_cast<int>(std::strtol(p, &p, 10))), p += *p == ',';
    } else
      dir = a;
  }
  std::vector<std::string> files;
  for (const auto& e : std::filesystem::directory_iterator(dir))
    if (e.path().extension() == ".obj") files.push_back(e.path().string());
  std::sort(files.begin(), files.end());
  std::vector<Row> rows(ks.size());
  for (const std::string& f : files) {
    auto mesh = ReadMeshFile(f);
    if (!mesh.ok()) continue;
    const Sampled s = Sample(*mesh, n, noise, 1);
    for (size_t j = 0; j < ks.size(); ++j) {
      const auto t0 = Clock::now();
      auto est = EstimateNormals(s.points, NormalEstimationParams{ks[j]});
      rows[j].seconds += std::chrono::duration<double>(Clock::now() - t0).count();
      if (!est.ok()) return std::fprintf(stderr, "%s: %s\n", f.c_str(), est.status().ToString().c_str()), 1;
      rows[j].points += s.points.size();
      Score(s, *est, &rows[j]);
      if (verbose && s.closed) {
        Row one;
        Score(s, *est, &one);
        std::printf("  k %d %s: abs(cos) %.4f outward %.4f\n", ks[j], f.c_str(), one.cos_all, one.outward_closed);
      }
    }
  }
  std::printf("%zu meshes from %s, %d points each, noise %.4g x diagonal\n", files.size(), dir.c_str(), n, noise);
  std::printf(
      "| k | mean abs(cos), all (%d) | mean abs(cos), closed (%d) | outward share, closed | closed meshes >= 90%% "
      "outward | ms per 10k points |\n|---|---|---|---|---|---|\n",
      rows[0].meshes, rows[0].closed);
  for (size_t j = 0; j < ks.size(); ++j) {
    const Row& r = rows[j];
    std::printf("| %d | %.4f | %.4f | %.4f | %d of %d | %.1f |\n", ks[j], r.cos_all / r.meshes,
                r.cos_closed / std::max(r.closed, 1), r.outward_closed / std::max(r.closed, 1), r.closed_mostly_right,
                r.closed, 1e3 * r.seconds / (static_cast<double>(r.points) / 10000));
  }
  return 0;
}
