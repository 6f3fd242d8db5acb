#include "core/metrics.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace verifybench {

template <int Dim>
double rotation_error_deg(const Rigid<Dim>& estimate, const Rigid<Dim>& truth) {
  const double trace = (truth.linear().transpose() * estimate.linear()).trace();
  const double cosine = std::clamp((trace - (Dim - 2)) / 2.0, -1.0, 1.0);
  return std::acos(cosine) * 180.0 / M_PI;
}

template <int Dim>
double translation_error(const Rigid<Dim>& estimate, const Rigid<Dim>& truth) {
  return (estimate.translation() - truth.translation()).norm();
}

InlierScores inlier_scores(const std::vector<int>& selected,
                           const std::vector<std::uint8_t>& labels) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  std::size_t true_positive = 0;
  for (int i : selected) {
    if (i < 0 || static_cast<std::size_t>(i) >= labels.size()) {
      throw std::out_of_range("inlier_scores: selected index " + std::to_string(i) +
                              " outside the " + std::to_string(labels.size()) + " labels");
    }
    true_positive += labels[static_cast<std::size_t>(i)] ? 1 : 0;
  }
  const auto positives = static_cast<std::size_t>(std::count(labels.begin(), labels.end(), 1));
  InlierScores s{nan, nan, nan};
  if (!selected.empty()) s.precision = double(true_positive) / double(selected.size());
  if (positives > 0) s.recall = double(true_positive) / double(positives);
  if (!std::isnan(s.precision) && !std::isnan(s.recall)) {
    const double sum = s.precision + s.recall;
    s.f1 = sum > 0.0 ? 2.0 * s.precision * s.recall / sum : 0.0;
  }
  return s;
}

template double rotation_error_deg<2>(const Rigid<2>&, const Rigid<2>&);
template <int Dim>
SelectionGeometry selection_geometry(const Correspondences<Dim>& corr,
                                     const std::vector<int>& selected) {
  SelectionGeometry g;
  if (selected.empty()) {
    g.lever_arm = std::numeric_limits<double>::quiet_NaN();
    return g;
  }
  auto distinct = [&](const typename Correspondences<Dim>::Points& pts) {
    std::vector<std::array<double, Dim>> v;
    for (int i : selected) {
      std::array<double, Dim> a;
      for (int d = 0; d < Dim; ++d) a[static_cast<std::size_t>(d)] = pts(d, i);
      v.push_back(a);
    }
    std::sort(v.begin(), v.end());
    return static_cast<int>(std::unique(v.begin(), v.end()) - v.begin());
  };
  g.distinct = std::min(distinct(corr.source), distinct(corr.target));
  Eigen::Matrix<double, Dim, 1> mean = Eigen::Matrix<double, Dim, 1>::Zero();
  for (int i : selected) mean += corr.source.col(i);
  mean /= static_cast<double>(selected.size());
  Eigen::Matrix<double, Dim, Dim> cov = Eigen::Matrix<double, Dim, Dim>::Zero();
  for (int i : selected) {
    const Eigen::Matrix<double, Dim, 1> d = corr.source.col(i) - mean;
    cov += d * d.transpose();
  }
  cov /= static_cast<double>(selected.size());
  const Eigen::Matrix<double, Dim, 1> ev =
      Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, Dim, Dim>>(cov).eigenvalues();  // ascending
  g.lever_arm = std::sqrt(std::max(0.0, ev(0) + ev(1)));
  return g;
}

template SelectionGeometry selection_geometry<2>(const Correspondences<2>&, const std::vector<int>&);
template SelectionGeometry selection_geometry<3>(const Correspondences<3>&, const std::vector<int>&);
template double rotation_error_deg<3>(const Rigid<3>&, const Rigid<3>&);
template double translation_error<2>(const Rigid<2>&, const Rigid<2>&);
template double translation_error<3>(const Rigid<3>&, const Rigid<3>&);

}  // namespace verifybench
