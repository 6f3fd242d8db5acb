// `quatro`: Quatro (Lim, Lee, Myung, "A Single Correspondence Is Enough: Robust Global
// Registration to Avoid Degeneracy in Urban Environments", ICRA 2022), TEASER's pipeline with the
// rotation restricted to a quasi-SO(3):
//   1. max clique inlier selection on the TIMs (TEASER's step; Eq. (1) graph at --eps, exact
//      maximum clique, the authors' default PMC_EXACT);
//   2. quasi-SO(3) estimation: roll and pitch of a ground vehicle are taken as ~0,
//      so R = R_z(theta) and the z component of every TIM residual b - R a is independent of
//      theta; theta comes from GNC-TLS on the xy components of the chain TIMs of the clique (TIM p
//      joins the p-th and (p+1)-th member, closed), each weighted fit in closed form
//      (detail/quatro.hpp weighted_yaw: theta = atan2(sum w a x b, sum w a . b)), TIM noise bound
//      2 beta. The rotation is exactly R_z(theta): its z axis is (0, 0, 1) whatever the true roll
//      and pitch (the method's definition, not a failure);
//   3. COTE, TEASER's component-wise translation by adaptive voting over t_i = q_i - R m_i of the
//      whole max clique (the authors' default; --quatro-cote-rotation-inliers: of the rotation
//      inliers only, the members both of whose chain TIMs are inliers); the inliers are the
//      members within beta of the estimate on every axis (the authors' final inliers).
//   beta = --inlier-threshold (the authors' noise_bound, with noise_bound_coeff 1). The GNC stage
//   takes the gnc-* settings; its defaults (100 iterations, factor 1.4, cost change 1e-6) are the
//   authors' solver defaults, their KITTI config uses 50 iterations and 1.1e-4.
// In 2D the quasi-SO(3) is the whole SO(2): the same steps run, the yaw being the planar rotation
// and COTE voting on two axes.
#include <cmath>

#include "cliques/max_clique.hpp"
#include "core/timer.hpp"
#include "solvers/detail/gnc.hpp"
#include "solvers/detail/graph_stage.hpp"
#include "solvers/detail/quatro.hpp"
#include "solvers/registry.hpp"

namespace verifybench {

namespace {

class QuatroSolver : public SolverBase<QuatroSolver> {
 public:
  bool solves_concurrently() const override { return true; }

  template <int Dim>
  Result<Dim> run(const Correspondences<Dim>& corr, const SolverParams& params) const {
    using Mat = Eigen::Matrix<double, Dim, Dim>;
    const auto deadline = deadline_after(params.time_limit_s);
    Result<Dim> result;
    const auto built = build_graph_stage(corr, params, result);
    if (!built) return result;

    StopWatch search_clock;
    // Step 1: the maximum clique.
    const RobinSelection clique = robin_select(*built, /*max_clique=*/true, seconds_until(deadline),
                                               params.threads, params.seed);
    const std::vector<int>& selected = clique.vertices;
    const std::size_t k = selected.size();
    YawGncOutcome yaw;
    if (k >= 2) {  // TEASER++ (and Quatro) give up on a clique of one
      // Step 2: the yaw by GNC-TLS on the xy components of the chain TIMs.
      Eigen::Matrix<double, Dim, Eigen::Dynamic> a, b;
      chain_tims(corr, selected, a, b);
      GncSettings settings;
      settings.max_iterations = params.gnc.max_iterations;
      settings.mu_factor = params.gnc.mu_factor;
      settings.cost_threshold = params.gnc.cost_threshold;
      settings.noise_bound = 2.0 * params.inlier_threshold;
      settings.deadline = deadline;
      yaw = gnc_tls_yaw(a.template topRows<2>(), b.template topRows<2>(), settings);
      result.counters.iterations = yaw.gnc.iterations;
      if (yaw.gnc.fitted) {
        Mat R = Mat::Identity();
        R.template topLeftCorner<2, 2>() = Eigen::Rotation2Dd(yaw.yaw).toRotationMatrix();
        // Step 3: COTE over the clique, or over its rotation inliers.
        std::vector<int> members;
        if (params.quatro.cote_rotation_inliers) {
          for (std::size_t v = 0; v < k; ++v) {  // TIMs v - 1 and v both end at member v
            if (yaw.gnc.weights[(v + k - 1) % k] > 0.5 && yaw.gnc.weights[v] > 0.5) {
              members.push_back(selected[v]);
            }
          }
        }
        if (members.empty()) members = selected;  // as the authors do with no rotation inlier
        const CoteOutcome<Dim> cote =
            component_translation(corr, R, members, params.inlier_threshold);
        result.T_target_source.linear() = R;
        result.T_target_source.translation() = cote.t;
        result.inliers = cote.inliers;  // ascending: the clique is
      }
    }
    result.times.search_ms = search_clock.ms();
    decide(result, corr, params, !clique.stopped && !yaw.gnc.timed_out);
    return result;
  }

  /// R_z(theta) is a rotation: the inliers lie within beta sqrt(Dim) of one rigid motion, a
  /// clique of Eq. (1) at 2 beta sqrt(Dim), and they are members of a clique of the graph at eps.
  template <int Dim>
  std::optional<int> bound(const Correspondences<Dim>& corr, const SolverParams& params,
                           int part_size) const {
    const double box =
        2.0 * params.inlier_threshold * std::sqrt(static_cast<double>(Dim)) * (1.0 + 1e-9);
    return clique_number_bound(corr, params, std::min(params.eps, box), part_size);
  }
};

}  // namespace

void register_quatro_solver() {
  SolverRegistry::add(
      {"quatro",
       "Quatro (Lim, Lee, Myung, ICRA 2022): TEASER's max clique of the TIM graph (Eq. 1), "
       "quasi-SO(3) rotation (yaw only) by GNC-TLS on the TIMs' xy components, translation by "
       "component-wise adaptive voting",
       [] { return std::make_unique<QuatroSolver>(); }});
}

const ParamFamily& quatro_param_family() {
  using K = ParamField::Kind;
  static const ParamFamily family{
      "quatro",
      "quatro (its yaw stage takes the gnc-* settings)",
      {bind(&SolverParams::quatro, &QuatroParams::cote_rotation_inliers,
            {"quatro-cote-rotation-inliers",
             "quatro_cote_rotation_inliers",
             "",
             "translation (COTE) from the rotation inliers of the max clique only, not the whole "
             "clique (the authors' using_rot_inliers_when_estimating_cote; off by default)",
             K::flag,
             0,
             1,
             "",
             {},
             {},
             {}})}};
  return family;
}

}  // namespace verifybench
