#include "core/correspondences.hpp"

#include <Eigen/Cholesky>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace verifybench {

template <int Dim>
void validate(const Correspondences<Dim>& corr) {
  if (corr.source.cols() != corr.target.cols()) {
    std::ostringstream msg;
    msg << "mismatched correspondence set: " << corr.source.cols() << " source points but "
        << corr.target.cols() << " target points";
    throw std::invalid_argument(msg.str());
  }
  for (const auto* side : {&corr.source, &corr.target}) {
    for (Eigen::Index i = 0; i < side->cols(); ++i) {
      for (int d = 0; d < Dim; ++d) {
        const double v = (*side)(d, i);
        if (!std::isfinite(v)) {
          std::ostringstream msg;
          msg << "non-finite coordinate in correspondence " << i << ": "
              << (side == &corr.source ? "source" : "target") << "."
              << "xyz"[d] << " = " << v;
          throw std::invalid_argument(msg.str());
        }
      }
    }
  }
  if (!corr.score.empty() && static_cast<Eigen::Index>(corr.score.size()) != corr.size()) {
    std::ostringstream msg;
    msg << "score count " << corr.score.size() << " does not match correspondence count "
        << corr.size();
    throw std::invalid_argument(msg.str());
  }
  for (std::size_t i = 0; i < corr.score.size(); ++i) {
    if (!std::isfinite(corr.score[i])) {
      std::ostringstream msg;
      msg << "non-finite score of correspondence " << i << ": " << corr.score[i];
      throw std::invalid_argument(msg.str());
    }
  }
  if (corr.prior) {
    const auto& P = corr.prior->covariance;
    const bool finite = P.allFinite() && corr.prior->T_target_source.matrix().allFinite();
    if (!finite || !P.isApprox(P.transpose(), 1e-9) || P.llt().info() != Eigen::Success) {
      throw std::invalid_argument(
          "pose prior: covariance must be finite, symmetric and positive definite");
    }
  }
}

template <int Dim>
void validate(const LabeledSet<Dim>& set) {
  validate(set.corr);
  if (!set.truth.labels.empty() &&
      static_cast<Eigen::Index>(set.truth.labels.size()) != set.corr.size()) {
    std::ostringstream msg;
    msg << "label count " << set.truth.labels.size() << " does not match correspondence count "
        << set.corr.size();
    throw std::invalid_argument(msg.str());
  }
}

template void validate<2>(const Correspondences<2>&);
template void validate<3>(const Correspondences<3>&);
template void validate<2>(const LabeledSet<2>&);
template void validate<3>(const LabeledSet<3>&);

}  // namespace verifybench
