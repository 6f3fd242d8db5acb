#pragma once
// Hypothesis scoring for the RANSAC family: the points once in single precision, centred, one
// array per coordinate (so the loops vectorise), and two scores with early exit.
#include <cstdint>
#include <vector>

#include "core/correspondences.hpp"

namespace verifybench::detail {

/// Centred float copy of a set: source/target coordinate d of point i is s[d][i] / t[d][i], with
/// the centroids removed in double first (KITTI coordinates reach hundreds of metres).
struct ScoringPoints {
  int dim = 3;
  int n = 0;
  std::vector<float> s[3], t[3];
  Eigen::Vector3d source_centroid = Eigen::Vector3d::Zero();
  Eigen::Vector3d target_centroid = Eigen::Vector3d::Zero();
};

template <int Dim>
ScoringPoints make_scoring_points(const Correspondences<Dim>& corr);

/// A motion in the centred frames: q - c_t = R (m - c_s) + t', row-major R.
struct CentredMotion {
  float R[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  float t[3] = {0, 0, 0};
};

template <int Dim>
CentredMotion centre(const ScoringPoints& pts, const Rigid<Dim>& T);

/// Residuals ||R m_i + t - q_i||^2 < thr2 counted. Stops early and returns some value <= `bound`
/// once the count cannot exceed `bound` any more; the count is exact whenever it exceeds it.
int count_inliers(const ScoringPoints& pts, const CentredMotion& T, float thr2, int bound);

/// MSAC cost sum_i min(r_i^2, thr2) in integer units of thr2 / kMsacUnits (integers sum in any
/// order to the same value, so every SIMD path gives the same result). Stops early and returns
/// some value >= `bound` once the cost cannot fall under `bound`; exact whenever below it.
constexpr std::int64_t kMsacUnits = 4096;
std::int64_t msac_cost(const ScoringPoints& pts, const CentredMotion& T, float thr2,
                       std::int64_t bound);

}  // namespace verifybench::detail
