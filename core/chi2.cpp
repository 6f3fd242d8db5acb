#include "core/chi2.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace verifybench {

double regularized_gamma_p(double a, double x) {
  if (!(a > 0.0) || !(x >= 0.0)) throw std::invalid_argument("regularized_gamma_p: a > 0, x >= 0");
  if (x == 0.0) return 0.0;
  const double log_prefix = a * std::log(x) - x - std::lgamma(a);
  if (x < a + 1.0) {
    // P = x^a e^-x / Gamma(a + 1) * sum_k x^k / ((a + 1) ... (a + k))
    double term = 1.0 / a, sum = term;
    for (int k = 1; k < 10000; ++k) {
      term *= x / (a + k);
      sum += term;
      if (std::abs(term) < std::abs(sum) * 1e-16) break;
    }
    return std::exp(log_prefix) * sum;
  }
  // Q = x^a e^-x / Gamma(a) * 1 / (x + 1 - a - 1 (1 - a) / (x + 3 - a - ...)), modified Lentz.
  constexpr double kTiny = 1e-300;
  double b = x + 1.0 - a, c = 1.0 / kTiny, d = 1.0 / b, h = d;
  for (int i = 1; i < 10000; ++i) {
    const double an = -i * (i - a);
    b += 2.0;
    d = an * d + b;
    if (std::abs(d) < kTiny) d = kTiny;
    c = b + an / c;
    if (std::abs(c) < kTiny) c = kTiny;
    d = 1.0 / d;
    const double delta = d * c;
    h *= delta;
    if (std::abs(delta - 1.0) < 1e-16) break;
  }
  return 1.0 - std::exp(log_prefix) * h;
}

double chi2_cdf(double x, int dof) {
  if (dof < 1) throw std::invalid_argument("chi2_cdf: dof must be >= 1");
  return x <= 0.0 ? 0.0 : regularized_gamma_p(0.5 * dof, 0.5 * x);
}

double chi2_quantile(double p, int dof) {
  if (!(p > 0.0 && p < 1.0) || dof < 1) {
    std::ostringstream msg;
    msg << "chi2_quantile: p = " << p << " must be in (0, 1) and dof = " << dof << " >= 1";
    throw std::invalid_argument(msg.str());
  }
  double lo = 0.0, hi = dof + 10.0 * std::sqrt(2.0 * dof) + 10.0;
  while (chi2_cdf(hi, dof) < p) hi *= 2.0;
  for (int it = 0; it < 200 && hi - lo > 1e-12 * hi; ++it) {
    const double mid = 0.5 * (lo + hi);
    (chi2_cdf(mid, dof) < p ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

}  // namespace verifybench
