#include "core/rigid_fit.hpp"

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
template std::optional<Rigid<2>> fit_rigid<2>(const Correspondences<2>&);
template std::optional<Rigid<3>> fit_rigid<3>(const Correspondences<3>&);

}  // namespace verifybench
