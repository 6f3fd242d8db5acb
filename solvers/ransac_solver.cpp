// `ransac`: hypothesise-and-verify baseline. Minimal samples of Dim points (2 in 2D, 3 in 3D) drawn
// without replacement, degenerate samples skipped, consensus by residual threshold, least-squares
// refit on the best consensus set. Fixed count (the paper's RANSAC-10K) or adaptive
// k = log(1 - p) / log(1 - w^s), capped at ransac_iterations.
#include <algorithm>
#include <cmath>
#include <random>

#include "core/rigid_fit.hpp"
#include "solvers/consensus.hpp"
#include "solvers/registry.hpp"
#include "solvers/timer.hpp"

namespace verifybench {

namespace {

/// Samples whose points (nearly) coincide, or in 3D are (nearly) collinear, fix no motion.
template <int Dim>
bool degenerate(const Correspondences<Dim>& corr, const int* s, double min_dist) {
  const double d2 = min_dist * min_dist;
  for (int a = 0; a < Dim; ++a) {
    for (int b = a + 1; b < Dim; ++b) {
      if ((corr.source.col(s[a]) - corr.source.col(s[b])).squaredNorm() < d2) return true;
      if ((corr.target.col(s[a]) - corr.target.col(s[b])).squaredNorm() < d2) return true;
    }
  }
  if constexpr (Dim == 3) {
    const Eigen::Vector3d u = corr.source.col(s[1]) - corr.source.col(s[0]);
    const Eigen::Vector3d v = corr.source.col(s[2]) - corr.source.col(s[0]);
    // Triangle height under min_dist: the sample is close to a line.
    const double longest = std::max({u.norm(), v.norm(), (v - u).norm()});
    if (u.cross(v).norm() < min_dist * longest) return true;
  }
  return false;
}

class RansacSolver : public SolverBase<RansacSolver> {
 public:
  template <int Dim>
  Result<Dim> run(const Correspondences<Dim>& corr, const SolverParams& params) const {
    Result<Dim> result;
    StopWatch total;
    const int n = static_cast<int>(corr.size());
    const auto deadline = deadline_after(params.time_limit_s);
    std::mt19937_64 rng(params.seed);
    std::vector<int> pool(static_cast<std::size_t>(n));
    for (int i = 0; i < n; ++i) pool[static_cast<std::size_t>(i)] = i;

    std::vector<int> sample(Dim);
    std::size_t best_count = 0;
    Rigid<Dim> best_T = Rigid<Dim>::Identity();
    long long needed = params.ransac_iterations;
    bool finished = true;
    StopWatch search_clock;
    const double min_dist = params.inlier_threshold;  // sample points must be resolvable
    for (long long it = 0; n >= Dim && it < needed; ++it) {
      if ((it & 255) == 255 && SteadyClock::now() >= deadline) {
        finished = false;
        break;
      }
      ++result.counters.iterations;
      // Partial Fisher-Yates: Dim distinct indices, uniform without replacement.
      for (int k = 0; k < Dim; ++k) {
        std::uniform_int_distribution<int> pick(k, n - 1);
        std::swap(pool[static_cast<std::size_t>(k)], pool[static_cast<std::size_t>(pick(rng))]);
      }
      if (degenerate(corr, pool.data(), min_dist)) continue;
      std::copy(pool.begin(), pool.begin() + Dim, sample.begin());
      const auto T = fit_rigid(corr, sample);
      if (!T) continue;
      const std::size_t count = consensus_count(corr, *T, params.inlier_threshold);
      if (count <= best_count) continue;
      best_count = count;
      best_T = *T;
      if (params.ransac_adaptive) {
        const double w = double(best_count) / n;
        const double miss = 1.0 - std::pow(w, Dim);
        const double k =
            miss <= 0.0 ? 0.0 : std::log(1.0 - params.ransac_confidence) / std::log(miss);
        needed =
            std::min<long long>(params.ransac_iterations, static_cast<long long>(std::ceil(k)));
      }
    }
    result.times.search_ms = search_clock.ms();

    StopWatch fit_clock;
    if (best_count > 0) take_consensus_with_refit(corr, best_T, params.inlier_threshold, result);
    result.times.fit_ms = fit_clock.ms();
    decide(result, params, finished);
    return result;
  }
};

}  // namespace

void register_ransac_solver() {
  SolverRegistry::add({"ransac",
                       "RANSAC: minimal samples (2 in 2D, 3 in 3D) without replacement, fixed "
                       "10,000 iterations by default (the paper's RANSAC-10K) or adaptive, seeded",
                       [] { return std::make_unique<RansacSolver>(); }});
}

}  // namespace verifybench
