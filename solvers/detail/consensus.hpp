#pragma once
// Consensus of a motion hypothesis (the correspondences it explains), shared by the hypothesise-
// and-verify solvers (ransac, mac).
#include <vector>

#include "core/rigid_fit.hpp"
#include "solvers/solver.hpp"

namespace verifybench {

/// Calls f(i) for each correspondence that T maps to within `threshold` of its target.
template <int Dim, class F>
void for_each_inlier(const Correspondences<Dim>& corr, const Rigid<Dim>& T, double threshold,
                     F&& f) {
  const double t2 = threshold * threshold;
  const Eigen::Matrix<double, Dim, Dim> R = T.linear();
  const Eigen::Matrix<double, Dim, 1> t = T.translation();
  for (Eigen::Index i = 0; i < corr.size(); ++i) {
    if ((R * corr.source.col(i) + t - corr.target.col(i)).squaredNorm() < t2)
      f(static_cast<int>(i));
  }
}

template <int Dim>
std::size_t consensus_count(const Correspondences<Dim>& corr, const Rigid<Dim>& T,
                            double threshold) {
  std::size_t count = 0;
  for_each_inlier(corr, T, threshold, [&](int) { ++count; });
  return count;
}

template <int Dim>
std::vector<int> consensus_set(const Correspondences<Dim>& corr, const Rigid<Dim>& T,
                               double threshold) {
  std::vector<int> inliers;
  for_each_inlier(corr, T, threshold, [&](int i) { inliers.push_back(i); });
  return inliers;
}

/// Sets result.inliers to the consensus of T, then refits by least squares on it and keeps the
/// refit when it explains at least as many correspondences.
template <int Dim>
void take_consensus_with_refit(const Correspondences<Dim>& corr, const Rigid<Dim>& T,
                               double threshold, Result<Dim>& result) {
  result.inliers = consensus_set(corr, T, threshold);
  result.T_target_source = T;
  if (auto refit = fit_rigid(corr, result.inliers)) {
    std::vector<int> refined = consensus_set(corr, *refit, threshold);
    if (refined.size() >= result.inliers.size()) {
      result.inliers = std::move(refined);
      result.T_target_source = *refit;
    }
  }
}

}  // namespace verifybench
