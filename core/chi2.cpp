#include "core/chi2.hpp"

#include <boost/math/distributions/chi_squared.hpp>
#include <boost/math/special_functions/gamma.hpp>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace verifybench {

double regularized_gamma_p(double a, double x) {
  if (!(a > 0.0) || !(x >= 0.0)) throw std::invalid_argument("regularized_gamma_p: a > 0, x >= 0");
  return boost::math::gamma_p(a, x);
}

double chi2_cdf(double x, int dof) {
  if (dof < 1 || !(x >= 0.0)) throw std::invalid_argument("chi2_cdf: dof >= 1 and x >= 0");
  return boost::math::cdf(boost::math::chi_squared_distribution<double>(dof), x);
}

double chi2_quantile(double p, int dof) {
  if (!(p > 0.0 && p < 1.0) || dof < 1) {
    std::ostringstream msg;
    msg << "chi2_quantile: p = " << p << " must be in (0, 1) and dof = " << dof << " >= 1";
    throw std::invalid_argument(msg.str());
  }
  return boost::math::quantile(boost::math::chi_squared_distribution<double>(dof), p);
}

}  // namespace verifybench
