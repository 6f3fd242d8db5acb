#include "core/rigid_fit.hpp"

#include <Eigen/Eigenvalues>

#include <numeric>
#include <stdexcept>

namespace verifybench {

template <int Dim>
std::optional<Rigid<Dim>> fit_rigid(const Correspondences<Dim>& corr,
                                    const std::vector<int>& indices,
                                    const std::vector<double>& weights) {
  using Vec = Eigen::Matrix<double, Dim, 1>;
  using Mat = Eigen::Matrix<double, Dim, Dim>;
  if (!weights.empty() && weights.size() != indices.size()) {
    throw std::invalid_argument("fit_rigid: weights must be empty or match the index count");
  }
  auto weight = [&](std::size_t k) { return weights.empty() ? 1.0 : weights[k]; };

  double total = 0.0;
  int used = 0;
  Vec mean_s = Vec::Zero(), mean_t = Vec::Zero();
  for (std::size_t k = 0; k < indices.size(); ++k) {
    const double w = weight(k);
    if (w <= 0.0) continue;
    total += w;
    ++used;
    mean_s += w * corr.source.col(indices[k]);
    mean_t += w * corr.target.col(indices[k]);
  }
  if (used < 2 || !(total > 0.0)) return std::nullopt;
  mean_s /= total;
  mean_t /= total;

  // Cross-covariance H = sum w (m - m_bar)(q - q_bar)^T; R = V D U^T with H = U S V^T.
  Mat H = Mat::Zero();
  double spread = 0.0;
  for (std::size_t k = 0; k < indices.size(); ++k) {
    const double w = weight(k);
    if (w <= 0.0) continue;
    const Vec ds = corr.source.col(indices[k]) - mean_s;
    H += w * ds * (corr.target.col(indices[k]) - mean_t).transpose();
    spread += w * ds.squaredNorm();
  }
  return rigid_from_moments<Dim>(H, spread, mean_s, mean_t);
}

template <int Dim>
std::optional<Rigid<Dim>> fit_rigid(const Correspondences<Dim>& corr) {
  std::vector<int> all(static_cast<std::size_t>(corr.size()));
  std::iota(all.begin(), all.end(), 0);
  return fit_rigid(corr, all);
}

template std::optional<Rigid<2>> fit_rigid<2>(const Correspondences<2>&, const std::vector<int>&,
                                              const std::vector<double>&);
template std::optional<Rigid<3>> fit_rigid<3>(const Correspondences<3>&, const std::vector<int>&,
                                              const std::vector<double>&);
namespace {

template <int Dim>
bool side_spans(const typename Correspondences<Dim>::Points& pts, const std::vector<int>& selected) {
  Eigen::Matrix<double, Dim, 1> mean = Eigen::Matrix<double, Dim, 1>::Zero();
  for (int i : selected) mean += pts.col(i);
  mean /= static_cast<double>(selected.size());
  Eigen::Matrix<double, Dim, Dim> cov = Eigen::Matrix<double, Dim, Dim>::Zero();
  for (int i : selected) {
    const Eigen::Matrix<double, Dim, 1> d = pts.col(i) - mean;
    cov += d * d.transpose();
  }
  cov /= static_cast<double>(selected.size());
  const auto ev = Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, Dim, Dim>>(
                      cov, Eigen::EigenvaluesOnly).eigenvalues();  // ascending
  const double largest = ev(Dim - 1);
  if (!(largest > 1e-24 * (1.0 + mean.squaredNorm()))) return false;  // all coincident
  return Dim == 2 || ev(Dim - 2) > 1e-10 * largest;                   // 3D: not collinear
}

}  // namespace

template <int Dim>
bool pins_motion(const Correspondences<Dim>& corr, const std::vector<int>& selected) {
  if (static_cast<int>(selected.size()) < (Dim == 2 ? 2 : 3)) return false;
  return side_spans<Dim>(corr.source, selected) && side_spans<Dim>(corr.target, selected);
}

template bool pins_motion<2>(const Correspondences<2>&, const std::vector<int>&);
template bool pins_motion<3>(const Correspondences<3>&, const std::vector<int>&);
template std::optional<Rigid<2>> fit_rigid<2>(const Correspondences<2>&);
template std::optional<Rigid<3>> fit_rigid<3>(const Correspondences<3>&);

}  // namespace verifybench
