#pragma once
// Graduated non-convexity with the truncated least squares cost (GNC-TLS; Yang, Antonante,
// Tzoumas, Carlone, "Graduated Non-Convexity for Robust Spatial Perception", RA-L 2020), shared by
// `gnc-tls` (the rigid motion from all correspondences) and `teaser` (the rotation from TIMs).
//
// TLS: min_x sum_i min(r_i(x)^2, c^2), c the noise bound. GNC replaces it by a surrogate rho_mu,
// convex for mu -> 0 and equal to TLS for mu -> inf (the paper's Sec. III, TLS example), and
// alternates (Sec. IV, Algorithm 1) a weighted least-squares fit (the non-minimal solver) with the
// weights that minimise the Black-Rangarajan dual of rho_mu in closed form (Sec. IV, GNC-TLS weight
// update):
//   w_i = 1                               if r_i^2 <= mu / (mu + 1) c^2
//       = c / r_i sqrt(mu (mu + 1)) - mu  if in between
//       = 0                               if r_i^2 >= (mu + 1) / mu c^2,
// from mu_0 = c^2 / (2 r_max^2 - c^2) (rho_mu convex over the residuals of the unweighted fit),
// growing mu by a factor (1.4 in the paper) after each update. It stops when the weighted cost
// sum w_i r_i^2 changes by less than a threshold (TEASER++'s rule, the authors' implementation)
// or after a number of iterations.
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "core/timer.hpp"

namespace verifybench {

struct GncSettings {
  int max_iterations = 100;
  double mu_factor = 1.4;
  double cost_threshold = 1e-6;
  double noise_bound = 0.1;  ///< c: a residual past it is an outlier of the TLS cost [m]
  SteadyClock::time_point deadline = SteadyClock::time_point::max();
};

struct GncOutcome {
  std::vector<double> weights;  ///< the last weights, in [0, 1]; > 0.5 marks an inlier
  int iterations = 0;           ///< weight updates made
  bool fitted = false;          ///< the first (unweighted) fit succeeded
  bool timed_out = false;       ///< the deadline passed before convergence
};

/// GNC-TLS over n residuals. `fit(weights)` solves the weighted least-squares problem and keeps
/// its model (false when the weights do not determine one: the last model then stays);
/// `residuals_sq(r2)` writes the squared residuals of the current model. The model the caller
/// holds at the end is the one whose residuals gave the returned weights.
template <class Fit, class ResidualsSq>
GncOutcome gnc_tls(int n, const GncSettings& s, Fit&& fit, ResidualsSq&& residuals_sq) {
  GncOutcome out;
  out.weights.assign(static_cast<std::size_t>(n), 1.0);
  std::vector<double> r2(static_cast<std::size_t>(n));
  if (!fit(out.weights)) return out;
  out.fitted = true;
  residuals_sq(r2);

  const double c2 = s.noise_bound * s.noise_bound;
  double r2_max = 0.0;
  for (double r : r2) r2_max = std::max(r2_max, r);
  // mu_0 = c^2 / (2 r_max^2 - c^2); <= 0 when every residual of the least-squares fit is within
  // c / sqrt(2): all weights stay 1.
  double mu = c2 / (2.0 * r2_max - c2);
  if (!(mu > 0.0) || !std::isfinite(mu)) return out;

  double previous = std::numeric_limits<double>::infinity();
  for (int it = 0; it < s.max_iterations; ++it) {
    double cost = 0.0;  // the weighted least-squares cost of the current fit
    const double upper = (mu + 1.0) / mu * c2, lower = mu / (mu + 1.0) * c2;
    for (std::size_t i = 0; i < r2.size(); ++i) {
      cost += out.weights[i] * r2[i];
      out.weights[i] = r2[i] >= upper   ? 0.0
                       : r2[i] <= lower ? 1.0
                                        : std::sqrt(c2 * mu * (mu + 1.0) / r2[i]) - mu;
    }
    ++out.iterations;
    if (std::abs(cost - previous) < s.cost_threshold) break;
    previous = cost;
    mu *= s.mu_factor;
    if (SteadyClock::now() >= s.deadline) {
      out.timed_out = true;
      break;
    }
    if (!fit(out.weights)) break;
    residuals_sq(r2);
  }
  return out;
}

}  // namespace verifybench
