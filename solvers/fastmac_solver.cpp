// `fastmac`: FastMAC (Zhang, Zhang, Wang, Li, "FastMAC: Stochastic Spectral Sampling of
// Correspondence Graph", CVPR 2024): MAC on a small sample of the correspondences that keeps the
// high-frequency part of the graph's generalized degree signal:
//   1. the correspondence graph C: Eq. (1) at eps;
//   2. the generalized degree signal d = W 1 of the second-order graph W = S (.) (S S), S = C + I,
//      and its high-pass response f = L d, L = diag(d) - W (detail/fastmac.hpp);
//   3. stochastic spectral sampling: floor(ratio n) correspondences drawn without replacement
//      with probability proportional to |f_i|, seeded from params.seed;
//   4. MAC on the subgraph of C the sample induces (maximal cliques of at least mac_min_clique,
//      node-guided selection, at most mac_max_cliques enumerated), one motion per kept clique;
//   5. each motion scored by its consensus on ALL correspondences (within inlier_threshold); the
//      best wins (ties to the earlier clique) and is refit by least squares on its consensus.
// Steps 2 and 5 run on the worker pool (params.threads) with index-ordered reductions: the result
// is the same for any thread count. 2D is the same construction on planar points.
#include <atomic>

#include "core/parallel.hpp"
#include "core/random.hpp"
#include "core/rigid_fit.hpp"
#include "core/timer.hpp"
#include "solvers/detail/consensus.hpp"
#include "solvers/detail/fastmac.hpp"
#include "solvers/detail/graph_stage.hpp"
#include "solvers/registry.hpp"

namespace verifybench {

namespace {

/// The sampling stream's id under params.seed.
constexpr std::uint64_t kSamplingStream = 0xFA57AC;

class FastMacSolver : public SolverBase<FastMacSolver> {
 public:
  bool solves_concurrently() const override { return true; }

  template <int Dim>
  Result<Dim> run(const Correspondences<Dim>& corr, const SolverParams& params) const {
    const auto deadline = deadline_after(params.time_limit_s);
    Result<Dim> result;
    const auto built = build_graph_stage(corr, params, result);
    if (!built) return result;
    const BitGraph& g = *built;

    StopWatch search_clock;
    WorkerPool pool(params.threads);
    const auto signal = fastmac::degree_signal(g, pool, deadline);
    if (!signal) {
      result.times.search_ms = search_clock.ms();
      decide(result, corr, params, false);
      return result;
    }
    std::vector<double> weight(signal->high.size());
    for (std::size_t i = 0; i < weight.size(); ++i) weight[i] = std::abs(signal->high[i]);
    const int n = g.size();
    const std::vector<int> sample = fastmac::weighted_sample(
        weight, fastmac::sample_size(n, params.fastmac.ratio, params.mac.min_clique),
        derive_seed(params.seed, {kSamplingStream}));

    MaximalCliqueParams mp;
    mp.min_size = params.mac.min_clique;
    mp.max_cliques = params.mac.max_cliques;
    mp.time_limit_s = seconds_until(deadline);
    const auto mac = fastmac::node_guided_cliques(fastmac::induced_subgraph(g, sample), mp);
    result.counters.branch_nodes = mac.nodes;

    // Step 5: every kept clique's motion scored on all correspondences, reduced in order.
    const int hypotheses = static_cast<int>(mac.cliques.size());
    std::vector<std::size_t> count(static_cast<std::size_t>(hypotheses), 0);
    std::vector<Rigid<Dim>> motion(count.size(), Rigid<Dim>::Identity());
    std::atomic<bool> late{false};
    pool.parallel_for(hypotheses, [&](int h) {
      if (late.load(std::memory_order_relaxed)) return;
      if ((h & 15) == 15 && SteadyClock::now() >= deadline) {
        late = true;
        return;
      }
      std::vector<int> members;
      for (int a : mac.cliques[static_cast<std::size_t>(h)])
        members.push_back(sample[static_cast<std::size_t>(a)]);
      const auto T = fit_rigid(corr, members);
      if (!T) return;
      motion[static_cast<std::size_t>(h)] = *T;
      count[static_cast<std::size_t>(h)] = consensus_count(corr, *T, params.inlier_threshold);
    });
    result.counters.iterations = hypotheses;
    std::size_t best = 0, best_count = 0;
    for (std::size_t h = 0; h < count.size(); ++h) {
      if (count[h] > best_count) best_count = count[h], best = h;
    }
    result.times.search_ms = search_clock.ms();

    StopWatch fit_clock;
    if (best_count > 0)
      take_consensus_with_refit(corr, motion[best], params.inlier_threshold, result);
    result.times.fit_ms = fit_clock.ms();
    decide(result, corr, params, mac.complete && !late.load());
    return result;
  }

  /// The reported inliers are one motion's consensus (take_consensus_with_refit).
  template <int Dim>
  std::optional<int> bound(const Correspondences<Dim>& corr, const SolverParams& params,
                           int part_size) const {
    return consensus_bound(corr, params, part_size);
  }
};

}  // namespace

void register_fastmac_solver() {
  SolverRegistry::add(
      {"fastmac",
       "FastMAC (Zhang et al., CVPR 2024): stochastic spectral sampling of the correspondence "
       "graph (Laplacian high-pass of the generalized degree), then MAC on the sample; the best "
       "consensus on all correspondences wins, least-squares refit",
       [] { return std::make_unique<FastMacSolver>(); }});
}

const ParamFamily& fastmac_param_family() {
  using K = ParamField::Kind;
  static const ParamFamily family{
      "fastmac",
      "fastmac (graph at --eps; its MAC stage takes the mac-* settings)",
      {bind(&SolverParams::fastmac, &FastMacParams::ratio,
            {"fastmac-ratio",
             "fastmac_ratio",
             "R",
             "fraction of the correspondences the spectral sampling keeps, at least "
             "--mac-min-clique of them (paper: 1% to 50%, little loss down to 5-10%)",
             K::real,
             1e-9,
             1,
             "a value in (0, 1]",
             {},
             {},
             {}})}};
  return family;
}

}  // namespace verifybench
