// `robin-gnc`: KISS-Matcher's verifier (Lim et al., "KISS-Matcher: Fast and Robust Point Cloud
// Registration Revisited", ICRA 2025: its k-core-based graph-theoretic pruning and GNC solver),
// as the authors' code (ROBINMatching, RobustRegistrationSolver) runs it:
//   1. ROBIN's graph-theoretic outlier pruning (Shi, Yang, Carlone, ICRA 2021): the compatibility
//      graph of the pairwise invariant | ||q_i - q_j|| - ||m_i - m_j|| | <= eps (ROBIN's
//      Points3dRegCompCheck with KISS-Matcher's robin_noise_bound, which is Eq. (1) here), then
//      its max k-core (the vertices of the largest core number; KISS-Matcher's default
//      robin_mode "max_core", chosen over "max_clique" as faster and no worse) or, with
//      --robin-mode 1, its maximum clique;
//   2. rotation by GNC-TLS (detail/gnc.hpp) on the chain of TIMs over the pruned set (TIM p joins
//      the p-th and (p+1)-th survivor, closed), TIM noise bound 2 beta (the authors double the
//      solver's bound for TIMs, as TEASER++ does); fewer than 2 inlier TIMs (weight > 0.5): no
//      solution, as in the authors' code;
//   3. translation by component-wise adaptive voting (COTE, TEASER's scalar TLS) over the whole
//      pruned set, not only the rotation inliers (the authors' solveForTranslation takes R * src
//      of every survivor); the inliers are the survivors within beta of the estimate on every
//      axis (the authors' translation inliers, their final ones).
//   beta = --inlier-threshold (KISS-Matcher's solver_noise_bound: 0.75 x the ROBIN bound by its
//   defaults, solver_noise_bound_gain 0.75 vs robin_noise_bound_gain 1.0; give
//   --inlier-threshold 0.75 x --eps to follow them). No refit: the motion is the estimate.
// In 2D the same steps run on planar TIMs (GNC-TLS over SO(2), voting on two axes).
#include <cmath>
#include <utility>

#include "core/rigid_fit.hpp"
#include "core/timer.hpp"
#include "solvers/detail/gnc.hpp"
#include "solvers/detail/graph_stage.hpp"
#include "solvers/detail/quatro.hpp"
#include "solvers/registry.hpp"

namespace verifybench {

namespace {

class RobinGncSolver : public SolverBase<RobinGncSolver> {
 public:
  bool solves_concurrently() const override { return true; }
  bool searches() const override { return false; }  // GNC converges from one start

  template <int Dim>
  Result<Dim> run(const Correspondences<Dim>& corr, const SolverParams& params) const {
    using Vec = Eigen::Matrix<double, Dim, 1>;
    using Mat = Eigen::Matrix<double, Dim, Dim>;
    const auto deadline = deadline_after(params.time_limit_s);
    Result<Dim> result;
    const auto built = build_graph_stage(corr, params, result);
    if (!built) return result;

    StopWatch search_clock;
    // Step 1: ROBIN's pruning.
    const RobinSelection pruned =
        robin_select(*built, params.robin.mode == RobinParams::kMaxClique, seconds_until(deadline),
                     params.threads, params.seed);
    const std::vector<int>& selected = pruned.vertices;
    GncOutcome gnc;
    if (selected.size() >= 2) {
      // Step 2: rotation by GNC-TLS on the chain TIMs, each fit the weighted Umeyama step without
      // means (TIMs carry no translation).
      Eigen::Matrix<double, Dim, Eigen::Dynamic> a, b;
      chain_tims(corr, selected, a, b);
      Mat R = Mat::Identity();
      const auto fit = [&](const std::vector<double>& w) {
        Mat H = Mat::Zero();
        double spread = 0.0;
        for (Eigen::Index p = 0; p < a.cols(); ++p) {
          H += w[static_cast<std::size_t>(p)] * a.col(p) * b.col(p).transpose();
          spread += w[static_cast<std::size_t>(p)] * a.col(p).squaredNorm();
        }
        const auto T = rigid_from_moments<Dim>(H, spread, Vec::Zero(), Vec::Zero());
        if (T) R = T->linear();
        return T.has_value();
      };
      const auto residuals_sq = [&](std::vector<double>& r2) {
        for (Eigen::Index p = 0; p < a.cols(); ++p) {
          r2[static_cast<std::size_t>(p)] = (b.col(p) - R * a.col(p)).squaredNorm();
        }
      };
      GncSettings settings;
      settings.max_iterations = params.gnc.max_iterations;
      settings.mu_factor = params.gnc.mu_factor;
      settings.cost_threshold = params.gnc.cost_threshold;
      settings.noise_bound = 2.0 * params.inlier_threshold;
      settings.deadline = deadline;
      gnc = gnc_tls(static_cast<int>(a.cols()), settings, fit, residuals_sq);
      result.counters.iterations = gnc.iterations;
      int rotation_inliers = 0;
      for (double w : gnc.weights) rotation_inliers += w > 0.5;
      if (gnc.fitted && rotation_inliers >= 2) {
        // Step 3: COTE over every survivor.
        const CoteOutcome<Dim> cote =
            component_translation(corr, R, selected, params.inlier_threshold);
        result.T_target_source.linear() = R;
        result.T_target_source.translation() = cote.t;
        result.inliers = cote.inliers;  // ascending: the selection is
      }
    }
    result.times.search_ms = search_clock.ms();
    decide(result, corr, params, !pruned.stopped && !gnc.timed_out);
    return result;
  }

  /// The inliers lie within beta of one rigid motion on every axis, so within beta sqrt(Dim): a
  /// clique of Eq. (1) at 2 beta sqrt(Dim) (as teaser's bound); in the max-clique mode also a
  /// clique of the graph at eps. (A k-core is no clique: the max-core mode has the first only.)
  template <int Dim>
  std::optional<int> bound(const Correspondences<Dim>& corr, const SolverParams& params,
                           int part_size) const {
    const double box =
        2.0 * params.inlier_threshold * std::sqrt(static_cast<double>(Dim)) * (1.0 + 1e-9);
    const bool clique = params.robin.mode == RobinParams::kMaxClique;
    return clique_number_bound(corr, params, clique ? std::min(params.eps, box) : box, part_size);
  }
};

}  // namespace

void register_robin_gnc_solver() {
  SolverRegistry::add(
      {"robin-gnc",
       "KISS-Matcher's verifier (Lim et al., ICRA 2025): ROBIN pruning (Shi et al., ICRA 2021) by "
       "the max k-core of the Eq. 1 graph (or max clique), GNC-TLS rotation on its chain TIMs, "
       "translation by component-wise voting over the pruned set",
       [] { return std::make_unique<RobinGncSolver>(); }});
}

const ParamFamily& robin_param_family() {
  using K = ParamField::Kind;
  static const ParamFamily family{
      "robin",
      "robin-gnc (KISS-Matcher; its rotation stage takes the gnc-* settings)",
      {bind(&SolverParams::robin, &RobinParams::mode,
            {"robin-mode",
             "robin_mode",
             "M",
             "ROBIN pruning: 0 = max k-core of the Eq. (1) graph (KISS-Matcher's default "
             "robin_mode max_core), 1 = its maximum clique (max_clique)",
             K::integer,
             0,
             1,
             "0 (max core) or 1 (max clique)",
             {},
             {},
             {}})}};
  return family;
}

}  // namespace verifybench
