#pragma once
// Chi-square distribution: the gates of JCBB's individual and joint compatibility tests, from
// Boost.Math (Debian libboost-dev), behind the project's own domain checks.
namespace verifybench {

/// Regularised lower incomplete gamma P(a, x) = gamma(a, x) / Gamma(a), a > 0, x >= 0.
double regularized_gamma_p(double a, double x);

/// CDF of chi-square with `dof` degrees of freedom: P(dof / 2, x / 2).
double chi2_cdf(double x, int dof);

/// x with chi2_cdf(x, dof) = p, for p in (0, 1) and dof >= 1.
/// Throws std::invalid_argument outside that domain.
double chi2_quantile(double p, int dof);

}  // namespace verifybench
