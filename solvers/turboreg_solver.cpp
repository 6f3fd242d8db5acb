// `turboreg`: TurboReg (Yan, Shi, Zhao, Wang, Cao, Wu, Li, "TurboReg: TurboClique for Robust and
// Efficient Point Cloud Registration", ICCV 2025), on the CPU (the authors publish a LibTorch/GPU
// version only); the steps of the paper and its code:
//   1. the TurboClique's highly constrained compatibility graph C: Eq. (1) at the stringent
//      tau = tau_ratio x eps (a small tau narrows each pair's noise, so three matches fix a
//      stable motion), less the pairs too close to fix one (the authors' mask: the sum of the
//      pair's source and target distances <= nms_radius);
//   2. SC2 weights G^ = C (.) (C C) on its edges (detail/sc2.hpp) and the K1 heaviest edges as
//      pivots (Pivot-Guided Search, pivot selection);
//   3. Pivot-Guided Search: per pivot (i, j) the K2 TurboCliques (3-cliques) (i, j, k) of highest
//      G^_ij + G^_ik + G^_jk, k from the ordered SC2 graph (O2Graph, k > j) by default;
//   4. a motion per TurboClique (3-point least squares), scored on all correspondences within
//      inlier_threshold by the chosen metric (IN / MAE / MSE); the best wins, ties to the
//      earlier clique (heavier pivot, then higher clique score);
//   5. post-refinement: reweighted refits on its inliers (as SC2-PCR's); the inliers are the
//      final motion's consensus.
// Steps 2-4 run on the worker pool (params.threads); every reduction is in index order, so the
// result is the same for any thread count. In 2D everything is the same with planar points (a
// TurboClique's three points also fix a planar motion).
#include <atomic>

#include "core/parallel.hpp"
#include "core/timer.hpp"
#include "solvers/detail/consensus.hpp"
#include "solvers/detail/graph_stage.hpp"
#include "solvers/detail/turboreg.hpp"
#include "solvers/registry.hpp"

namespace verifybench {

namespace {

/// Step 1's mask: removes the edges of pairs too close to fix a stable motion.
template <int Dim>
void drop_close_pairs(const Correspondences<Dim>& corr, double radius, BitGraph& g) {
  if (!(radius > 0.0)) return;
  for (int i = 0; i < g.size(); ++i) {
    std::vector<int> close;
    turboreg::for_each_later_neighbour(g, i, [&](int j) {
      if ((corr.source.col(i) - corr.source.col(j)).norm() +
              (corr.target.col(i) - corr.target.col(j)).norm() <=
          radius)
        close.push_back(j);
    });
    for (int j : close) turboreg::remove_edge(g, i, j);
  }
}

class TurboRegSolver : public SolverBase<TurboRegSolver> {
 public:
  bool solves_concurrently() const override { return true; }

  template <int Dim>
  Result<Dim> run(const Correspondences<Dim>& corr, const SolverParams& params) const {
    const auto deadline = deadline_after(params.time_limit_s);
    const TurboRegParams& tp = params.turboreg;
    Result<Dim> result;
    auto built = build_graph_stage(corr, params, result, tp.tau_ratio * params.eps);
    if (!built) return result;
    BitGraph& g = *built;
    drop_close_pairs(corr, tp.nms_radius, g);
    result.counters.graph_edges = g.edge_count();

    StopWatch search_clock;
    WorkerPool pool(params.threads);
    bool stopped = false;
    const auto pivots = turboreg::select_pivots(g, tp.pivots, pool, deadline, stopped);

    // Step 3: each pivot's TurboCliques, then all of them in pivot order.
    std::vector<std::vector<turboreg::Clique>> per_pivot(pivots.size());
    pool.parallel_for(static_cast<int>(pivots.size()), [&](int p) {
      per_pivot[static_cast<std::size_t>(p)] = turboreg::pivot_cliques(
          g, pivots[static_cast<std::size_t>(p)], tp.cliques_per_pivot, !tp.full_graph);
    });
    std::vector<turboreg::Clique> cliques;
    for (const auto& found : per_pivot) cliques.insert(cliques.end(), found.begin(), found.end());

    // Step 4: every TurboClique's motion and score; the winner reduced in clique order.
    const auto metric = static_cast<turboreg::Metric>(tp.metric);
    std::vector<double> score(cliques.size(), -1.0);
    std::vector<Rigid<Dim>> motion(cliques.size(), Rigid<Dim>::Identity());
    std::atomic<bool> late{false};
    pool.parallel_for(static_cast<int>(cliques.size()), [&](int c) {
      const auto s = static_cast<std::size_t>(c);
      if (late.load(std::memory_order_relaxed)) return;
      if ((c & 15) == 15 && SteadyClock::now() >= deadline) {
        late = true;
        return;
      }
      const auto T = turboreg::clique_motion(corr, cliques[s]);
      if (!T) return;
      motion[s] = *T;
      score[s] = turboreg::hypothesis_score(corr, *T, params.inlier_threshold, metric);
    });
    stopped |= late.load();
    result.counters.iterations = static_cast<long long>(cliques.size());
    std::ptrdiff_t best = -1;
    for (std::size_t c = 0; c < cliques.size(); ++c) {
      if (score[c] > 0.0 && (best < 0 || score[c] > score[static_cast<std::size_t>(best)]))
        best = static_cast<std::ptrdiff_t>(c);
    }
    result.times.search_ms = search_clock.ms();

    // Step 5: the winner's post-refinement; the inliers are its final consensus.
    StopWatch fit_clock;
    if (best >= 0) {
      result.T_target_source = turboreg::post_refine(corr, motion[static_cast<std::size_t>(best)],
                                                     params.inlier_threshold, tp.refine_iterations);
      result.inliers = consensus_set(corr, result.T_target_source, params.inlier_threshold);
    }
    result.times.fit_ms = fit_clock.ms();
    decide(result, corr, params, !stopped);
    return result;
  }

  /// The reported inliers are one motion's consensus.
  template <int Dim>
  std::optional<int> bound(const Correspondences<Dim>& corr, const SolverParams& params,
                           int part_size) const {
    return consensus_bound(corr, params, part_size);
  }
};

}  // namespace

void register_turboreg_solver() {
  SolverRegistry::add(
      {"turboreg",
       "TurboReg (Yan et al., ICCV 2025): Eq. (1) at a stringent tau, top-K1 SC2 pivot edges, "
       "pivot-guided search of K2 TurboCliques (3-cliques, O2Graph) each, 3-point fits scored "
       "by consensus, the best refined",
       [] { return std::make_unique<TurboRegSolver>(); }});
}

const ParamFamily& turboreg_param_family() {
  using K = ParamField::Kind;
  static const ParamFamily family{
      "turboreg",
      "turboreg (tau = ratio x --eps, scoring within --inlier-threshold; defaults: the authors' "
      "3DMatch commands and code)",
      {bind(&SolverParams::turboreg, &TurboRegParams::pivots,
            {"turboreg-pivots",
             "turboreg_pivots",
             "K",
             "K1: pivot edges, the heaviest by SC2 weight (authors: 2000)",
             K::integer,
             1,
             1 << 26,
             "an integer >= 1",
             {},
             {},
             {}}),
       bind(&SolverParams::turboreg, &TurboRegParams::cliques_per_pivot,
            {"turboreg-cliques-per-pivot",
             "turboreg_cliques_per_pivot",
             "K",
             "K2: TurboCliques kept per pivot, best by G^_ij + G^_ik + G^_jk (authors: 2)",
             K::integer,
             1,
             1 << 20,
             "an integer >= 1",
             {},
             {},
             {}}),
       bind(&SolverParams::turboreg, &TurboRegParams::tau_ratio,
            {"turboreg-tau-ratio",
             "turboreg_tau_ratio",
             "R",
             "the TurboClique graph is Eq. (1) at tau = R x eps (authors: tau 0.012 m where "
             "SC2-PCR and MAC take 0.1 m on 3DMatch: 0.12)",
             K::real,
             1e-9,
             1e6,
             "a finite value > 0",
             {},
             {},
             {}}),
       bind(&SolverParams::turboreg, &TurboRegParams::nms_radius,
            {"turboreg-nms-radius",
             "turboreg_nms_radius",
             "M",
             "drop pairs with ||m_i - m_j|| + ||q_i - q_j|| <= M from the graph, too close for a "
             "stable fit [m] (authors: 0.15 with FPFH, 0.10 with FCGF; 0 = keep all)",
             K::real,
             0,
             1e12,
             "a finite value >= 0",
             {},
             {},
             {}}),
       bind(&SolverParams::turboreg, &TurboRegParams::metric,
            {"turboreg-metric",
             "turboreg_metric",
             "M",
             "hypothesis score: 0 = inlier count (authors' IN, with FPFH), 1 = MAE "
             "sum (tau - r) / tau (with FCGF), 2 = MSE sum (tau - r)^2 / tau^2",
             K::integer,
             0,
             2,
             "0 (IN), 1 (MAE) or 2 (MSE)",
             {},
             {},
             {}}),
       bind(&SolverParams::turboreg, &TurboRegParams::full_graph,
            {"turboreg-full-graph",
             "turboreg_full_graph",
             "",
             "take the third vertex from the SC2 graph G^ rather than the ordered O2Graph "
             "(upper triangle, k > j; the authors' code)",
             K::flag,
             0,
             1,
             "",
             {},
             {},
             {}}),
       bind(&SolverParams::turboreg, &TurboRegParams::refine_iterations,
            {"turboreg-refine-iterations",
             "turboreg_refine_iterations",
             "K",
             "reweighted refits of the winning motion at most (authors: 20)",
             K::integer,
             0,
             1 << 20,
             "an integer >= 0",
             {},
             {},
             {}})}};
  return family;
}

}  // namespace verifybench
