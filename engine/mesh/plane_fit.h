// SPDX-License-Identifier: MIT
// Local plane fit by PCA: the normal of a point's neighbourhood is the eigenvector of the
// smallest eigenvalue of its 3x3 covariance (the direction the points spread least along).
#pragma once
#include <array>
#include <cstdint>
#include <vector>

namespace silk {

using Point3 = std::array<double, 3>;
using Matrix3 = std::array<std::array<double, 3>, 3>;

// Eigen-decomposition of a symmetric 3x3 matrix by cyclic Jacobi rotations: eigenvalues
// ascending and the unit eigenvectors to match (eigenvectors[i] belongs to eigenvalues[i]).
struct SymmetricEigen3 {
  Point3 eigenvalues;
  std::array<Point3, 3> eigenvectors;
};
SymmetricEigen3 EigenSymmetric3(const Matrix3& m);

// Unit normal of the least-squares plane through points[ids[0..count)] (covariance about their
// mean). Its sign is arbitrary (orientation is a separate step); a neighbourhood without a
// plane (all points equal) gives some unit vector, never NaN.
Point3 FitPlaneNormal(const std::vector<Point3>& points, const int32_t* ids, int32_t count);

}  // namespace silk
