// SPDX-License-Identifier: MIT
// Covariance of a neighbourhood and its Jacobi eigen-decomposition.
#include "mesh/plane_fit.h"

#include <algorithm>
#include <cmath>

namespace silk {

namespace {

// One Jacobi rotation in the (p, q) plane that zeroes m[p][q]; v collects the rotations.
void Rotate(Matrix3* m, Matrix3* v, int p, int q) {
  Matrix3& a = *m;
  if (a[p][q] == 0) return;
  const double theta = (a[q][q] - a[p][p]) / (2 * a[p][q]);
  const double t = std::fabs(theta) > 1e150
                       ? 0.5 / theta
                       : (theta >= 0 ? 1.0 : -1.0) / (std::fabs(theta) + std::sqrt(theta * theta + 1));
  const double c = 1 / std::sqrt(t * t + 1), s = t * c;
  // J: identity with J[p][p] = J[q][q] = c, J[p][q] = s, J[q][p] = -s.
  Matrix3 j{};
  for (int i = 0; i < 3; ++i) j[i][i] = 1;
  j[p][p] = c, j[q][q] = c, j[p][q] = s, j[q][p] = -s;
  Matrix3 aj{}, r{};  // r = J^T A J
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 3; ++k) aj[i][k] = a[i][0] * j[0][k] + a[i][1] * j[1][k] + a[i][2] * j[2][k];
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 3; ++k) r[i][k] = j[0][i] * aj[0][k] + j[1][i] * aj[1][k] + j[2][i] * aj[2][k];
  r[p][q] = r[q][p] = 0;
  a = r;
  Matrix3 vj{};
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 3; ++k) vj[i][k] = (*v)[i][0] * j[0][k] + (*v)[i][1] * j[1][k] + (*v)[i][2] * j[2][k];
  *v = vj;
}

}  // namespace

SymmetricEigen3 EigenSymmetric3(const Matrix3& m) {
  Matrix3 a = m, v{};
  for (int i = 0; i < 3; ++i) v[i][i] = 1;
  for (int sweep = 0; sweep < 32; ++sweep) {
    const double off = a[0][1] * a[0][1] + a[0][2] * a[0][2] + a[1][2] * a[1][2];
    const double diag = a[0][0] * a[0][0] + a[1][1] * a[1][1] + a[2][2] * a[2][2];
    if (off == 0 || off <= 1e-32 * diag) break;
    Rotate(&a, &v, 0, 1);
    Rotate(&a, &v, 0, 2);
    Rotate(&a, &v, 1, 2);
  }
  std::array<int, 3> idx{0, 1, 2};
  std::sort(idx.begin(), idx.end(), [&](int x, int y) { return a[x][x] < a[y][y] || (a[x][x] == a[y][y] && x < y); });
  SymmetricEigen3 e;
  for (int r = 0; r < 3; ++r) {
    e.eigenvalues[r] = a[idx[r]][idx[r]];
    for (int i = 0; i < 3; ++i) e.eigenvectors[r][i] = v[i][idx[r]];  // column idx[r] of V
  }
  return e;
}

Point3 FitPlaneNormal(const std::vector<Point3>& points, const int32_t* ids, int32_t count) {
  Point3 mean{0, 0, 0};
  for (int32_t i = 0; i < count; ++i)
    for (int a = 0; a < 3; ++a) mean[a] += points[ids[i]][a];
  for (double& x : mean) x /= std::max(count, 1);
  Matrix3 cov{};
  for (int32_t i = 0; i < count; ++i) {
    const Point3& p = points[ids[i]];
    const Point3 d{p[0] - mean[0], p[1] - mean[1], p[2] - mean[2]};
    for (int r = 0; r < 3; ++r)
      for (int c = r; c < 3; ++c) cov[r][c] += d[r] * d[c];
  }
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < r; ++c) cov[r][c] = cov[c][r];
  Point3 n = EigenSymmetric3(cov).eigenvectors[0];
  const double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  if (!(len > 0) || !std::isfinite(len)) return {0, 0, 1};
  for (double& x : n) x /= len;
  return n;
}

}  // namespace silk
