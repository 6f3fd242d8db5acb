#include "acceptance/prior_gate.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Geometry>
#include <cmath>

#include "core/chi2.hpp"

namespace verifybench {

template <int Dim>
Eigen::Matrix<double, kPoseDof<Dim>, 1> prior_perturbation(const Rigid<Dim>& T,
                                                           const Rigid<Dim>& T0) {
  const Rigid<Dim> E = T * T0.inverse();
  Eigen::Matrix<double, kPoseDof<Dim>, 1> delta;
  if constexpr (Dim == 2) {
    delta(0) = std::atan2(E.linear()(1, 0), E.linear()(0, 0));
    delta.template tail<2>() = E.translation();
  } else {
    const Eigen::AngleAxisd aa(Eigen::Matrix3d(E.linear()));
    delta.template head<3>() = aa.angle() * aa.axis();
    delta.template tail<3>() = E.translation();
  }
  return delta;
}

template <int Dim>
std::optional<double> prior_distance2(const Correspondences<Dim>& corr, const Rigid<Dim>& T) {
  if (!corr.prior) return std::nullopt;
  const auto delta = prior_perturbation<Dim>(T, corr.prior->T_target_source);
  // P is symmetric positive definite (validate(correspondences)): d^2 = delta^T P^-1 delta.
  return delta.dot(corr.prior->covariance.ldlt().solve(delta));
}

template <int Dim>
bool inside_prior_gate(double distance2, double confidence) {
  return distance2 <= chi2_quantile(confidence, kPoseDof<Dim>);
}

#define VB_INSTANTIATE(D)                                                                          \
  template Eigen::Matrix<double, kPoseDof<D>, 1> prior_perturbation<D>(const Rigid<D>&,            \
                                                                      const Rigid<D>&);            \
  template std::optional<double> prior_distance2<D>(const Correspondences<D>&, const Rigid<D>&); \
  template bool inside_prior_gate<D>(double, double);
VB_INSTANTIATE(2)
VB_INSTANTIATE(3)
#undef VB_INSTANTIATE

}  // namespace verifybench
