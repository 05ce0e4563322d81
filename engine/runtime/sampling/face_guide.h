// SPDX-License-Identifier: MIT
// FaceGuide: scores a face (or a lone edge) the grammar is about to close against the input's
// points, so face guidance (runtime/sampling/face_guide_stage.h) can keep connectivity ids whose
// faces lie on the input's surface and turn their normals the way the input's normals point.
#pragma once
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "mesh/nearest_points.h"
#include "tokenizer/cleanup/quantize.h"

namespace silk {

class SurfaceGuide;

// What face guidance does with a connectivity id whose faces stray past the tolerance.
enum class FaceGuidance : int32_t {
  kOff = 0,   // nothing (the former ids exactly)
  kHard = 1,  // removed from the legal set (the best-scoring ones kept when none passes)
  kSoft = 2,  // its logit lowered by kFaceSoftPenalty per tolerance unit past the tolerance
};
const char* FaceGuidanceName(FaceGuidance g);  // "off", "hard", "soft"
// "off" / "hard" / "soft" -> *out; false (nothing written) for any other text.
bool ParseFaceGuidanceName(const std::string& text, FaceGuidance* out);

// libsilk's defaults (a model.json may name its own: sampling.face_guidance / face_tolerance),
// chosen by the quality protocol (docs/runtime.md, "Face guidance"): off, because neither form
// met its aims on the bundled model and both cost CD and time; 4 cells for whoever turns it on.
inline constexpr FaceGuidance kDefaultFaceGuidance = FaceGuidance::kOff;
inline constexpr double kDefaultFaceTolerance = 4.0;

// A face's normal may turn this far from the input's normals (up to sign) before it strays.
inline constexpr double kFaceAngleLimitDegrees = 60.0;
// Two faces on one edge fold (turn their wound normals more than a right angle apart, the
// surface doubling back) when the angle between them, measured inside the pair (180 deg: flat,
// 0: one on top of the other), is below this. Reference meshes rarely do (none of about 10,000
// interior edges of 9 dev meshes below 45 deg, at most 4 % of a mesh's below 90: a blade, the
// tiger); the bundled model's unguided outputs fold at 61 % of theirs (test subset of 10). 90
// beat 45 on that subset on every figure (docs/runtime.md, "Folds").
inline constexpr double kFaceFoldLimitDegrees = 90.0;
// A full fold (0 deg) scores 1 + kFaceFoldSpan, rising linearly in the cosine from 1 at the limit.
inline constexpr double kFaceFoldSpan = 3.0;
// Soft form: logit penalty per unit of score past 1 (score 1 = at the tolerance), capped.
inline constexpr double kFaceSoftPenalty = 4.0;
inline constexpr double kFaceSoftPenaltyMax = 40.0;

// Built once per generation (best of N: once per input) from the encoder's points (rows of 6
// floats in the model frame: xyz, normal) and the distance field of their grid cells. Scores are
// in units of the tolerance: a face scores max(d / tolerance, a), where d is the largest distance
// in cells from its corners, edge midpoints and centroid to the nearest cell holding an input
// point, and a = (1 - |cos|) / (1 - cos kFaceAngleLimitDegrees) with |cos| the mean agreement, up
// to sign, of its normal with the normals of the input points nearest its centroid and corners.
// A score <= 1 passes. A face whose distance part is past 1 scores by it alone (the normal
// could not make it pass; the nearest-point query is skipped).
class FaceGuide {
 public:
  FaceGuide(std::shared_ptr<const SurfaceGuide> field, const std::vector<float>& points, double tolerance);

  double tolerance() const { return tolerance_; }
  // Distance (cells) from cell q to the nearest cell holding an input point.
  double CellDistance(const QVec& q) const { return Distance(q.x, q.y, q.z, 1); }
  // Index of the input point nearest grid position q (its normal: Normal(index)).
  int32_t NearestPoint(const QVec& q) const;
  // Score of triangle (a, b, c); n_a, n_b, n_c: NearestPoint of the corners (cached by callers).
  double FaceScore(const QVec& a, const QVec& b, const QVec& c, int32_t n_a, int32_t n_b, int32_t n_c) const;
  // Distance part alone of FaceScore (no normal: for positions judged in bulk).
  double FaceDistance(const QVec& a, const QVec& b, const QVec& c) const;
  // Fold score of faces (x, y, p) and (x, y, q) sharing edge (x, y), orientation-free: p and q
  // on opposite sides of the edge (a flat pair) score 0, at kFaceFoldLimitDegrees 1, on top of
  // each other 1 + kFaceFoldSpan. A degenerate face (p or q on the edge's line) scores 0.
  double FoldScore(const QVec& x, const QVec& y, const QVec& p, const QVec& q) const;
  // Score of an edge alone (distance only: its ends, midpoint and quarter points).
  double EdgeScore(const QVec& a, const QVec& b) const;
  // The same without its ends (a position still to be chosen: surface guidance judges that).
  double EdgeInterior(const QVec& a, const QVec& b) const;

 private:
  // Distance (cells) from the grid cell nearest (x, y, z) / scale (scale 1..4) to the nearest
  // cell holding an input point.
  double Distance(int32_t x2, int32_t y2, int32_t z2, int32_t scale) const;
  std::shared_ptr<const SurfaceGuide> field_;
  NearestPointIndex index_;      // the input points in grid units (cell centres at integers)
  std::vector<Point3> normals_;  // unit normals (zero when a point had none)
  std::vector<float> root_;      // sqrt of every squared cell distance the grid holds
  double tolerance_;
  double angle_scale_;  // 1 / (1 - cos limit)
  double fold_cos_;     // cos kFaceFoldLimitDegrees
};

}  // namespace silk
