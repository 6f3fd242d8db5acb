// `mac`: maximal cliques as hypotheses, as MAC (Zhang et al., CVPR 2023) does. Enumerate the
// maximal cliques of the correspondence graph (Eq. 1) of at least mac_min_clique vertices
// (for_each_maximal_clique in max_clique.hpp), keep for every
// vertex the largest maximal clique containing it (node-guided selection), fit each kept clique
// (Umeyama) and score it by its consensus: the correspondences within inlier_threshold under its
// motion. The best hypothesis wins; its consensus set is refit by least squares.
#include <algorithm>

#include "cliques/max_clique.hpp"
#include "core/rigid_fit.hpp"
#include "core/timer.hpp"
#include "solvers/detail/consensus.hpp"
#include "solvers/detail/graph_stage.hpp"
#include "solvers/registry.hpp"

namespace verifybench {

namespace {

class MacSolver : public SolverBase<MacSolver> {
 public:
  bool solves_concurrently() const override { return true; }

  template <int Dim>
  Result<Dim> run(const Correspondences<Dim>& corr, const SolverParams& params) const {
    Result<Dim> result;
    const auto built = build_graph_stage(corr, params, result);
    if (!built) return result;
    const BitGraph& g = *built;

    StopWatch search_clock;
    const int n = g.size();
    // Node-guided selection: the largest maximal clique through each vertex.
    std::vector<int> best_size(static_cast<std::size_t>(n), 0),
        best_id(static_cast<std::size_t>(n), -1);
    std::vector<std::vector<int>> kept;
    MaximalCliqueParams mp;
    mp.min_size = params.mac.min_clique;
    mp.max_cliques = params.mac.max_cliques;
    mp.time_limit_s = params.time_limit_s - result.times.graph_ms / 1000.0;
    long long nodes = 0;
    const bool complete = for_each_maximal_clique(
        g, mp,
        [&](const std::vector<int>& clique) {
          const int size = static_cast<int>(clique.size());
          bool improves = false;
          for (int u : clique) improves |= size > best_size[static_cast<std::size_t>(u)];
          if (!improves) return;
          for (int u : clique) {
            if (size > best_size[static_cast<std::size_t>(u)]) {
              best_size[static_cast<std::size_t>(u)] = size;
              best_id[static_cast<std::size_t>(u)] = static_cast<int>(kept.size());
            }
          }
          kept.push_back(clique);
        },
        &nodes);
    result.counters.branch_nodes = nodes;
    std::vector<int> ids(best_id);
    std::sort(ids.begin(), ids.end());
    ids.erase(std::unique(ids.begin(), ids.end()), ids.end());

    // Hypotheses: one motion per selected clique, scored by consensus.
    std::size_t best_count = 0;
    Rigid<Dim> best_T = Rigid<Dim>::Identity();
    for (int id : ids) {
      if (id < 0) continue;
      ++result.counters.iterations;
      const auto T = fit_rigid(corr, kept[static_cast<std::size_t>(id)]);
      if (!T) continue;
      const std::size_t count = consensus_count(corr, *T, params.inlier_threshold);
      if (count > best_count) best_count = count, best_T = *T;
    }
    result.times.search_ms = search_clock.ms();

    StopWatch fit_clock;
    if (best_count > 0) take_consensus_with_refit(corr, best_T, params.inlier_threshold, result);
    result.times.fit_ms = fit_clock.ms();
    decide(result, corr, params, complete);
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

void register_mac_solver() {
  SolverRegistry::add(
      {"mac",
       "MAC-style: maximal cliques (Bron-Kerbosch, node-guided selection) as hypotheses, "
       "best consensus wins, least-squares refit",
       [] { return std::make_unique<MacSolver>(); }});
}

const ParamFamily& mac_param_family() {
  using K = ParamField::Kind;
  static const ParamFamily family{"mac",
                                  "mac",
                                  {bind(&SolverParams::mac, &MacParams::max_cliques,
                                        {"mac-max-cliques",
                                         "mac_max_cliques",
                                         "K",
                                         "stop enumerating maximal cliques after K",
                                         K::integer,
                                         1,
                                         4.6e18,
                                         "an integer >= 1",
                                         {},
                                         {},
                                         {}}),
                                   bind(&SolverParams::mac, &MacParams::min_clique,
                                        {"mac-min-clique",
                                         "mac_min_clique",
                                         "K",
                                         "smallest maximal clique that makes a hypothesis",
                                         K::integer,
                                         2,
                                         1 << 30,
                                         "an integer >= 2",
                                         {},
                                         {},
                                         {}})}};
  return family;
}

}  // namespace verifybench
