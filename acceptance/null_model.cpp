#include "acceptance/null_model.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "core/chi2.hpp"

namespace verifybench {

namespace {
constexpr double kEulerGamma = 0.57721566490153286;
constexpr double kPi = 3.14159265358979324;
}  // namespace

NullFit fit_null(const std::vector<int>& scores) {
  if (scores.empty()) throw std::invalid_argument("null model: no null scores");
  NullFit f;
  f.scores = scores;
  f.draws = static_cast<int>(scores.size());
  double sum = 0.0;
  for (int s : scores) {
    if (s < 0) throw std::invalid_argument("null model: negative score " + std::to_string(s));
    sum += s;
    f.max = std::max(f.max, s);
  }
  f.mean = sum / f.draws;
  double ss = 0.0;
  for (int s : scores) ss += (s - f.mean) * (s - f.mean);
  f.sd = f.draws > 1 ? std::sqrt(ss / (f.draws - 1)) : 0.0;
  // Gumbel moments: variance = (pi beta)^2 / 6, mean = mu + gamma beta.
  f.scale = std::max(f.sd, kMinNullSd) * std::sqrt(6.0) / kPi;
  f.location = f.mean - kEulerGamma * f.scale;
  return f;
}

namespace {

/// fit_null with the mean moved by `sign` 3 standard errors and the floored sd scaled to its
/// chi-square bound at `quantile` (0.01: the upper bound, 0.99: the lower).
NullFit shifted_fit(const std::vector<int>& scores, double quantile, double sign) {
  if (scores.size() < 2) {
    throw std::invalid_argument("null model: " + std::to_string(scores.size()) +
                                " null scores; a spread needs at least 2");
  }
  NullFit f = fit_null(scores);
  const int k = f.draws;
  const double sd = std::max(kMinNullSd, std::max(f.sd, kMinNullSd) *
                                             std::sqrt((k - 1) / chi2_quantile(quantile, k - 1)));
  const double mean = f.mean + sign * 3.0 * sd / std::sqrt(static_cast<double>(k));
  f.scale = sd * std::sqrt(6.0) / kPi;
  f.location = mean - kEulerGamma * f.scale;
  return f;
}

}  // namespace

NullFit cautious_fit(const std::vector<int>& scores) { return shifted_fit(scores, 0.01, +1.0); }

NullFit optimistic_fit(const std::vector<int>& scores) { return shifted_fit(scores, 0.99, -1.0); }

double NullFit::p_value(int score) const {
  const double z = (score - 0.5 - location) / scale;
  double p = -std::expm1(-std::exp(-z));  // 1 - exp(-exp(-z)), accurate in the far tail
  const auto reached = std::count_if(scores.begin(), scores.end(), [&](int s) { return s >= score; });
  if (reached > 0) p = std::max(p, (1.0 + static_cast<double>(reached)) / (draws + 1.0));
  return std::clamp(p, 0.0, 1.0);
}

int NullFit::threshold(double alpha) const {
  // p_value is non-increasing in the score; start at the fitted quantile and step.
  int s = std::max(0, static_cast<int>(std::floor(location + 0.5 - scale * std::log(-std::log1p(-alpha)))) - 1);
  while (p_value(s) >= alpha) ++s;
  while (s > 0 && p_value(s - 1) < alpha) --s;
  return s;
}

}  // namespace verifybench
