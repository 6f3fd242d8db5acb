#include "loop/trajectory_metrics.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "core/rigid_fit.hpp"

namespace verifybench {

ApeStats absolute_pose_error(const std::vector<Rigid<3>>& estimate,
                             const std::vector<Rigid<3>>& truth) {
  if (estimate.size() != truth.size() || estimate.size() < 3) {
    throw std::invalid_argument("APE: " + std::to_string(estimate.size()) + " estimated and " +
                                std::to_string(truth.size()) +
                                " true poses (equal, at least 3)");
  }
  const int n = static_cast<int>(truth.size());
  Correspondences<3> c;
  c.source.resize(3, n);
  c.target.resize(3, n);
  std::vector<int> all(n);
  for (int i = 0; i < n; ++i) {
    c.source.col(i) = estimate[i].translation();
    c.target.col(i) = truth[i].translation();
    all[i] = i;
  }
  // Collinear positions leave the rotation about their line free: fall back to the translation
  // that matches the centroids (evo's Umeyama meets the same ambiguity).
  Rigid<3> align = Rigid<3>::Identity();
  if (const auto fit = fit_rigid<3>(c, all)) {
    align = *fit;
  } else {
    align.translation() = c.target.rowwise().mean() - c.source.rowwise().mean();
  }
  std::vector<double> e(n);
  double sum = 0, sum2 = 0;
  for (int i = 0; i < n; ++i) {
    e[i] = (align * c.source.col(i) - c.target.col(i)).norm();
    sum += e[i];
    sum2 += e[i] * e[i];
  }
  ApeStats s;
  s.poses = n;
  s.rmse = std::sqrt(sum2 / n);
  s.mean = sum / n;
  s.max = *std::max_element(e.begin(), e.end());
  std::sort(e.begin(), e.end());
  s.median = n % 2 ? e[n / 2] : 0.5 * (e[n / 2 - 1] + e[n / 2]);
  return s;
}

ClosureScore score_closures(const std::vector<bool>& accepted, const std::vector<bool>& correct,
                            int positives) {
  if (accepted.size() != correct.size()) {
    throw std::invalid_argument("closure scores: accepted and correct differ in length");
  }
  ClosureScore s;
  int correct_count = 0;
  for (std::size_t k = 0; k < accepted.size(); ++k) {
    correct_count += correct[k];
    if (accepted[k]) (correct[k] ? s.tp : s.fp) += 1;
  }
  if (correct_count > positives) {
    throw std::invalid_argument("closure scores: " + std::to_string(correct_count) +
                                " correct candidates but " + std::to_string(positives) +
                                " true closures");
  }
  s.fn = positives - s.tp;
  if (s.tp + s.fp > 0) s.precision = static_cast<double>(s.tp) / (s.tp + s.fp);
  if (positives > 0) s.recall = static_cast<double>(s.tp) / positives;
  if (s.tp > 0) s.f1 = 2.0 * s.precision * s.recall / (s.precision + s.recall);
  else if (positives > 0) s.f1 = 0.0;
  return s;
}

}  // namespace verifybench
