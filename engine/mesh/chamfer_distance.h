// Chamfer distance between a mesh's surface and a point set: the score that picks the best of
// several generated candidates (closest to the input), computed without Python.
#pragma once
#include <array>
#include <cstdint>
#include <vector>

#include "core/cancel_check.h"
#include "core/status.h"
#include "io/io_mesh.h"

namespace silk {

using Point3 = std::array<double, 3>;

// Nearest-neighbour queries over a fixed point set: a uniform grid of about two points per
// cell, searched ring by ring around the query's cell until no closer point can remain.
class NearestPointIndex {
 public:
  explicit NearestPointIndex(const std::vector<Point3>& points);
  struct Hit {
    double distance;  // Euclidean; +infinity when the set is empty
    int32_t index;    // into the points given to the constructor; -1 when the set is empty
  };
  // The nearest point (the first of the constructor's order among equally near ones).
  Hit Nearest(const Point3& q) const;
  // Euclidean distance to the nearest point; +infinity when the set is empty.
  double Distance(const Point3& q) const { return Nearest(q).distance; }

 private:
  std::array<int32_t, 3> CellOf(const Point3& q) const;
  void ScanCell(int32_t x, int32_t y, int32_t z, const Point3& q, double* best2, int32_t* best) const;
  std::vector<Point3> points_;        // sorted by cell
  std::vector<int32_t> ids_;          // constructor index of each points_ entry
  std::vector<int32_t> cell_start_;   // cells + 1 offsets into points_
  std::array<int32_t, 3> dims_{1, 1, 1};
  Point3 origin_{0, 0, 0};
  double cell_ = 1;
};

struct ChamferDistance {
  double a_to_b = 0;  // mean over a of the distance to the nearest point of b
  double b_to_a = 0;
  double value() const { return 0.5 * (a_to_b + b_to_a); }  // the symmetric Chamfer distance
};

// Mean nearest-neighbour distances both ways (+infinity towards an empty set).
ChamferDistance PointSetChamfer(const std::vector<Point3>& a, const std::vector<Point3>& b);
// The same, polling `cancel` every kChamferPollInterval queries (a million points take seconds):
// kCancelled when it asks to stop.
StatusOr<ChamferDistance> PointSetChamfer(const std::vector<Point3>& a, const std::vector<Point3>& b,
                                          const CancelCheck& cancel);
inline constexpr int64_t kChamferPollInterval = 4096;  // nearest-point queries (~10 ms)

// `samples` area-weighted surface samples of `mesh` (seeded) against `points`. A mesh without
// a face of positive area scores +infinity both ways, so it never beats one with faces.
ChamferDistance MeshToPointsChamfer(const IoMesh& mesh, const std::vector<Point3>& points, int32_t samples,
                                    uint64_t seed);
// The same, polling `cancel` (as PointSetChamfer above).
StatusOr<ChamferDistance> MeshToPointsChamfer(const IoMesh& mesh, const std::vector<Point3>& points, int32_t samples,
                                              uint64_t seed, const CancelCheck& cancel);

}  // namespace silk
