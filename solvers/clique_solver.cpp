// `clique`: the CliReg verifier. Correspondence graph (Eq. 1) -> maximum clique C* ->
// least-squares rigid fit on C* -> accept when |C*| reaches the threshold. One solver per clique
// algorithm of max_clique.hpp (`clique-<algorithm>`), and `clique` for the default one.
#include "cliques/max_clique.hpp"
#include "core/rigid_fit.hpp"
#include "core/timer.hpp"
#include "solvers/detail/graph_stage.hpp"
#include "solvers/registry.hpp"

namespace verifybench {

namespace {

class CliqueSolver : public SolverBase<CliqueSolver> {
 public:
  CliqueSolver(CliqueAlgorithm algorithm, bool concurrent)
      : algorithm_(std::move(algorithm)), concurrent_(concurrent) {}
  /// Not for the peer algorithms that search in a child process (cliquer, igraph).
  bool solves_concurrently() const override { return concurrent_; }

  template <int Dim>
  Result<Dim> run(const Correspondences<Dim>& corr, const SolverParams& params) const {
    Result<Dim> result;
    const auto built = build_graph_stage(corr, params, result);
    if (!built) return result;
    const BitGraph& graph = *built;

    StopWatch search_clock;
    CliqueSearchParams search;
    search.time_limit_s = params.time_limit_s - result.times.graph_ms / 1000.0;
    search.threads = params.threads;
    search.seed = params.seed;
    const CliqueSearchResult clique = algorithm_(graph, search);
    result.times.search_ms = search_clock.ms();
    result.counters.branch_nodes = clique.nodes;
    result.inliers = clique.clique;
    result.omega_upper_bound = clique.upper_bound;

    StopWatch fit_clock;
    if (auto T = fit_rigid(corr, result.inliers)) result.T_target_source = *T;
    result.times.fit_ms = fit_clock.ms();

    decide(result, corr, params, !clique.stopped);
    return result;
  }

  template <int Dim>
  std::optional<int> bound(const Correspondences<Dim>& corr, const SolverParams& params,
                           int part_size) const {
    return clique_number_bound(corr, params, params.eps, part_size);
  }

 private:
  CliqueAlgorithm algorithm_;
  bool concurrent_;
};

}  // namespace

void register_clique_solvers() {
  register_clique_algorithms();
  const CliqueAlgorithmInfo& default_algorithm = CliqueAlgorithms::get(kDefaultCliqueAlgorithm);
  SolverRegistry::add(
      {"clique",
       "CliReg: exact maximum clique (" + default_algorithm.name +
           ") on the pairwise-distance graph of Eq. (1), then least-squares fit",
       [run = default_algorithm.run, child = default_algorithm.child_process] {
         return std::make_unique<CliqueSolver>(run, !child);
       }});
  for (const CliqueAlgorithmInfo& info : CliqueAlgorithms::list()) {
    SolverRegistry::add({"clique-" + info.name,
                         "Eq. (1) graph, then " + info.description + ", then fit",
                         [run = info.run, child = info.child_process] {
                           return std::make_unique<CliqueSolver>(run, !child);
                         }});
  }
}

}  // namespace verifybench
