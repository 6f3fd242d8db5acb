// `teaser`: TEASER with known scale (Yang, Shi, Carlone, "TEASER: Fast and Certifiable Point Cloud
// Registration", T-RO 2020), as TEASER++ runs it:
//   1. inlier selection on the translation-invariant measurements (TIMs) m_j - m_i, q_j - q_i:
//      with the scale known, a TIM is consistent when | ||q_j - q_i|| - ||m_j - m_i|| | stays
//      within the noise, which is the correspondence graph of Eq. (1) (built once, with --eps; the
//      paper's bound is 2 beta, so --eps 2 x --inlier-threshold follows it), and its maximum clique
//      keeps the correspondences all of whose TIMs are consistent (max clique inlier selection);
//      TEASER++'s heuristic clique and max k-core (KCORE_HEU) are the other modes;
//   2. rotation by GNC-TLS (detail/gnc.hpp) on the TIMs of the selection, with the TIMs' noise
//      bound 2 beta (each TIM carries two points' noise);
//   3. translation by adaptive voting (detail/teaser.hpp), component-wise, on t_i = q_i - R m_i
//      of the rotation inliers, over the intervals [t_i - beta, t_i + beta];
//   beta = inlier_threshold. The inliers are TEASER++'s final ones: the rotation inliers whose
//   translation lies within beta of the estimate on every axis. No refit: the motion is TEASER's.
#include <cmath>
#include <cstdint>
#include <utility>

#include "cliques/max_clique.hpp"
#include "core/rigid_fit.hpp"
#include "core/timer.hpp"
#include "solvers/detail/gnc.hpp"
#include "solvers/detail/graph_stage.hpp"
#include "solvers/detail/teaser.hpp"
#include "solvers/registry.hpp"

namespace verifybench {

namespace {

/// Step 1: the selection by the chosen mode, ascending; `stopped` when a limit cut the search.
std::vector<int> select_inliers(const BitGraph& g, const SolverParams& params, double time_left_s,
                                bool& stopped) {
  register_clique_algorithms();
  CliqueSearchParams search;
  search.time_limit_s = time_left_s;
  search.threads = params.threads;
  search.seed = params.seed;
  stopped = false;
  if (params.teaser.inlier_selection == TeaserParams::kKcore) {
    if (auto core = max_kcore_selection(g, params.teaser.kcore_threshold)) return *core;
  }
  const CliqueSearchResult clique =
      params.teaser.inlier_selection == TeaserParams::kExact
          ? CliqueAlgorithms::get(kDefaultCliqueAlgorithm).run(g, search)
          : CliqueAlgorithms::get("greedy").run(g, search);
  stopped = clique.stopped;
  return clique.clique;
}

/// The TIMs of the selection: a chain (k -> k + 1, closed; TEASER++'s default) or every pair.
std::vector<std::pair<int, int>> tim_pairs(int k, bool complete) {
  std::vector<std::pair<int, int>> pairs;
  if (complete) {
    for (int a = 0; a < k; ++a)
      for (int b = a + 1; b < k; ++b) pairs.push_back({a, b});
  } else {
    for (int a = 0; a < k; ++a) pairs.push_back({a, (a + 1) % k});
  }
  return pairs;
}

class TeaserSolver : public SolverBase<TeaserSolver> {
 public:
  bool solves_concurrently() const override { return true; }

  template <int Dim>
  Result<Dim> run(const Correspondences<Dim>& corr, const SolverParams& params) const {
    using Vec = Eigen::Matrix<double, Dim, 1>;
    using Mat = Eigen::Matrix<double, Dim, Dim>;
    const auto deadline = deadline_after(params.time_limit_s);
    Result<Dim> result;
    const auto built = build_graph_stage(corr, params, result);
    if (!built) return result;

    StopWatch search_clock;
    bool stopped = false;
    const std::vector<int> selected =
        select_inliers(*built, params, seconds_until(deadline), stopped);
    const int k = static_cast<int>(selected.size());
    GncOutcome gnc;
    if (k >= 2) {  // TEASER++ gives up on a selection of one
      // Step 2: rotation by GNC-TLS on the TIMs, fit by the weighted Umeyama step without means.
      const auto pairs = tim_pairs(k, params.teaser.complete_tim_graph);
      std::vector<Vec> a(pairs.size()), b(pairs.size());
      for (std::size_t p = 0; p < pairs.size(); ++p) {
        const int i = selected[static_cast<std::size_t>(pairs[p].first)];
        const int j = selected[static_cast<std::size_t>(pairs[p].second)];
        a[p] = corr.source.col(j) - corr.source.col(i);
        b[p] = corr.target.col(j) - corr.target.col(i);
      }
      Mat R = Mat::Identity();
      const auto fit = [&](const std::vector<double>& w) {
        Mat H = Mat::Zero();
        double spread = 0.0;
        for (std::size_t p = 0; p < a.size(); ++p) {
          H += w[p] * a[p] * b[p].transpose();
          spread += w[p] * a[p].squaredNorm();
        }
        const auto T = rigid_from_moments<Dim>(H, spread, Vec::Zero(), Vec::Zero());
        if (T) R = T->linear();
        return T.has_value();
      };
      const auto residuals_sq = [&](std::vector<double>& r2) {
        for (std::size_t p = 0; p < a.size(); ++p) r2[p] = (b[p] - R * a[p]).squaredNorm();
      };
      GncSettings settings;
      settings.max_iterations = params.gnc.max_iterations;
      settings.mu_factor = params.gnc.mu_factor;
      settings.cost_threshold = params.gnc.cost_threshold;
      settings.noise_bound = 2.0 * params.inlier_threshold;
      settings.deadline = deadline;
      gnc = gnc_tls(static_cast<int>(a.size()), settings, fit, residuals_sq);
      result.counters.iterations = gnc.iterations;
      if (gnc.fitted) {
        result.T_target_source.linear() = R;
        estimate_translation(corr, params, selected, pairs, gnc.weights, result);
      }
    }
    result.times.search_ms = search_clock.ms();
    decide(result, corr, params, !stopped && !gnc.timed_out);
    return result;
  }

  /// The inliers lie within beta of the motion on every axis, so within beta sqrt(Dim): a clique
  /// of Eq. (1) at 2 beta sqrt(Dim) (as in consensus_bound); in the clique modes, also a clique of
  /// the graph at eps, the tighter bound at the default settings.
  template <int Dim>
  std::optional<int> bound(const Correspondences<Dim>& corr, const SolverParams& params,
                           int part_size) const {
    const double box =
        2.0 * params.inlier_threshold * std::sqrt(static_cast<double>(Dim)) * (1.0 + 1e-9);
    const bool clique = params.teaser.inlier_selection != TeaserParams::kKcore;
    return clique_number_bound(corr, params, clique ? std::min(params.eps, box) : box, part_size);
  }

 private:
  /// Step 3: a vertex is a rotation inlier when at least half of its TIMs are (TEASER++ keeps the
  /// root of each inlier TIM of its chain); each axis of t_i = q_i - R m_i is voted on separately.
  template <int Dim>
  static void estimate_translation(const Correspondences<Dim>& corr, const SolverParams& params,
                                   const std::vector<int>& selected,
                                   const std::vector<std::pair<int, int>>& pairs,
                                   const std::vector<double>& weights, Result<Dim>& result) {
    const std::size_t k = selected.size();
    std::vector<int> votes(k, 0), tims(k, 0);
    for (std::size_t p = 0; p < pairs.size(); ++p) {
      for (int end : {pairs[p].first, pairs[p].second}) {
        ++tims[static_cast<std::size_t>(end)];
        votes[static_cast<std::size_t>(end)] += weights[p] > 0.5;
      }
    }
    std::vector<int> kept;
    for (std::size_t v = 0; v < k; ++v) {
      if (2 * votes[v] >= tims[v] && votes[v] > 0) kept.push_back(selected[v]);
    }
    if (kept.empty()) return;
    const Eigen::Matrix<double, Dim, Dim> R = result.T_target_source.linear();
    const double beta = params.inlier_threshold;
    std::vector<std::uint8_t> inside(kept.size(), 1);
    std::vector<double> t(kept.size());
    for (int d = 0; d < Dim; ++d) {
      for (std::size_t v = 0; v < kept.size(); ++v) {
        t[v] = (corr.target.col(kept[v]) - R * corr.source.col(kept[v]))(d);
      }
      const double td = adaptive_vote(t, beta).estimate;
      result.T_target_source.translation()(d) = td;
      for (std::size_t v = 0; v < kept.size(); ++v) inside[v] &= std::abs(t[v] - td) <= beta;
    }
    for (std::size_t v = 0; v < kept.size(); ++v) {
      if (inside[v]) result.inliers.push_back(kept[v]);
    }
  }
};

}  // namespace

void register_teaser_solver() {
  SolverRegistry::add(
      {"teaser",
       "TEASER (Yang et al. 2020), known scale: max clique of the TIM graph (Eq. 1), GNC-TLS "
       "rotation on its TIMs, translation by component-wise adaptive voting",
       [] { return std::make_unique<TeaserSolver>(); }});
}

const ParamFamily& teaser_param_family() {
  using K = ParamField::Kind;
  static const ParamFamily family{
      "teaser",
      "teaser (its rotation stage takes the gnc-* settings)",
      {bind(&SolverParams::teaser, &TeaserParams::inlier_selection,
            {"teaser-inlier-selection",
             "teaser_inlier_selection",
             "M",
             "0 = exact max clique (TEASER++ PMC_EXACT, default), 1 = greedy heuristic clique "
             "(PMC_HEU), 2 = max k-core (KCORE_HEU)",
             K::integer,
             0,
             2,
             "0 (exact), 1 (heuristic) or 2 (kcore)",
             {},
             {},
             {}}),
       bind(&SolverParams::teaser, &TeaserParams::kcore_threshold,
            {"teaser-kcore-threshold",
             "teaser_kcore_threshold",
             "R",
             "kcore mode: take the max k-core when its core number exceeds R n, else the "
             "heuristic clique (TEASER++ kcore_heuristic_threshold: 0.5)",
             K::real,
             0,
             1,
             "a value in [0, 1]",
             {},
             {},
             {}}),
       bind(&SolverParams::teaser, &TeaserParams::complete_tim_graph,
            {"teaser-complete-tims",
             "teaser_complete_tims",
             "",
             "rotation on the TIMs of every pair of the selection, not of a chain (TEASER++ "
             "rotation_tim_graph COMPLETE; CHAIN is its default)",
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
