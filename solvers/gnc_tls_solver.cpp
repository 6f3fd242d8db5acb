// `gnc-tls`: graduated non-convexity with the truncated least squares cost on all
// correspondences, no graph (Yang, Antonante, Tzoumas, Carlone, "Graduated Non-Convexity for
// Robust Spatial Perception", RA-L 2020; its point cloud registration application). The non-minimal
// solver is the weighted closed-form rigid fit (Horn / Umeyama with weights), the residual
// r_i = ||R m_i + t - q_i||, the TLS bound c = inlier_threshold; the GNC loop is detail/gnc.hpp.
// The inliers are the correspondences of final weight > 0.5 (all within c of the last fit); the
// motion is their least-squares refit, which is the TLS optimum whenever they are its inlier set.
#include <numeric>

#include "core/rigid_fit.hpp"
#include "core/timer.hpp"
#include "solvers/detail/gnc.hpp"
#include "solvers/detail/graph_stage.hpp"
#include "solvers/registry.hpp"

namespace verifybench {

namespace {

class GncTlsSolver : public SolverBase<GncTlsSolver> {
 public:
  bool solves_concurrently() const override { return true; }
  bool searches() const override { return false; }  // GNC converges from one start

  template <int Dim>
  Result<Dim> run(const Correspondences<Dim>& corr, const SolverParams& params) const {
    const auto deadline = deadline_after(params.time_limit_s);
    Result<Dim> result;
    StopWatch search_clock;
    const int n = static_cast<int>(corr.size());
    std::vector<int> all(static_cast<std::size_t>(n));
    std::iota(all.begin(), all.end(), 0);
    Rigid<Dim> T = Rigid<Dim>::Identity();
    const auto fit = [&](const std::vector<double>& weights) {
      const auto fitted = fit_rigid(corr, all, weights);
      if (fitted) T = *fitted;
      return fitted.has_value();
    };
    const auto residuals_sq = [&](std::vector<double>& r2) {
      const Eigen::Matrix<double, Dim, Dim> R = T.linear();
      const Eigen::Matrix<double, Dim, 1> t = T.translation();
      for (int i = 0; i < n; ++i) {
        r2[static_cast<std::size_t>(i)] =
            (R * corr.source.col(i) + t - corr.target.col(i)).squaredNorm();
      }
    };
    GncSettings settings;
    settings.max_iterations = params.gnc.max_iterations;
    settings.mu_factor = params.gnc.mu_factor;
    settings.cost_threshold = params.gnc.cost_threshold;
    settings.noise_bound = params.inlier_threshold;
    settings.deadline = deadline;
    const GncOutcome gnc = gnc_tls(n, settings, fit, residuals_sq);
    result.counters.iterations = gnc.iterations;
    result.times.search_ms = search_clock.ms();

    StopWatch fit_clock;
    if (gnc.fitted) {
      for (int i = 0; i < n; ++i) {
        if (gnc.weights[static_cast<std::size_t>(i)] > 0.5) result.inliers.push_back(i);
      }
      result.T_target_source = T;
      if (auto refit = fit_rigid(corr, result.inliers)) result.T_target_source = *refit;
    }
    result.times.fit_ms = fit_clock.ms();
    decide(result, corr, params, !gnc.timed_out);
    return result;
  }

  /// A weight > 0.5 needs r < c (detail/gnc.hpp): the inliers are one motion's consensus.
  template <int Dim>
  std::optional<int> bound(const Correspondences<Dim>& corr, const SolverParams& params,
                           int part_size) const {
    return consensus_bound(corr, params, part_size);
  }
};

}  // namespace

void register_gnc_tls_solver() {
  SolverRegistry::add({"gnc-tls",
                       "GNC-TLS (Yang et al. 2020): graduated non-convexity on the truncated "
                       "least squares cost of all correspondences, weighted rigid fits, no graph",
                       [] { return std::make_unique<GncTlsSolver>(); }});
}

const ParamFamily& gnc_param_family() {
  using K = ParamField::Kind;
  static const ParamFamily family{
      "gnc",
      "GNC-TLS (gnc-tls, and the rotation stage of teaser)",
      {bind(&SolverParams::gnc, &GncParams::max_iterations,
            {"gnc-max-iterations",
             "gnc_max_iterations",
             "K",
             "GNC weight updates at most (paper and TEASER++: 100)",
             K::integer,
             1,
             1e9,
             "an integer >= 1",
             {},
             {},
             {}}),
       bind(&SolverParams::gnc, &GncParams::mu_factor,
            {"gnc-mu-factor",
             "gnc_mu_factor",
             "F",
             "mu <- F mu after each update (paper: 1.4)",
             K::real,
             1.0 + 1e-9,
             1e6,
             "a value > 1",
             {},
             {},
             {}}),
       bind(&SolverParams::gnc, &GncParams::cost_threshold,
            {"gnc-cost-threshold",
             "gnc_cost_threshold",
             "C",
             "stop when the weighted cost sum w r^2 changes by less [m^2] (TEASER++: 1e-6)",
             K::real,
             0,
             1e12,
             "a finite value >= 0",
             {},
             {},
             {}})}};
  return family;
}

}  // namespace verifybench
