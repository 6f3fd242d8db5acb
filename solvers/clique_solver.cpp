// `clique`: the CliReg verifier. Correspondence graph (Eq. 1) -> exact maximum clique C* ->
// least-squares rigid fit on C* -> accept when |C*| reaches the threshold.
#include "core/compatibility_graph.hpp"
#include "core/rigid_fit.hpp"
#include "solvers/max_clique.hpp"
#include "solvers/registry.hpp"
#include "solvers/timer.hpp"

namespace verifybench {

namespace {

class CliqueSolver : public SolverBase<CliqueSolver> {
 public:
  template <int Dim>
  Result<Dim> run(const Correspondences<Dim>& corr, const SolverParams& params) const {
    Result<Dim> result;
    StopWatch total;

    StopWatch graph_clock;
    const BitGraph graph = build_compatibility_graph(corr, GraphParams{params.eps, params.max_graph_bytes});
    result.times.graph_ms = graph_clock.ms();
    result.counters.graph_edges = graph.edge_count();

    StopWatch search_clock;
    CliqueSearchParams search;
    search.time_limit_s = params.time_limit_s - total.ms() / 1000.0;
    const CliqueSearchResult clique = max_clique(graph, search);
    result.times.search_ms = search_clock.ms();
    result.counters.branch_nodes = clique.nodes;
    result.inliers = clique.clique;

    StopWatch fit_clock;
    if (auto T = fit_rigid(corr, result.inliers)) result.T_target_source = *T;
    result.times.fit_ms = fit_clock.ms();

    decide(result, params, clique.optimal);
    return result;
  }
};

}  // namespace

void register_clique_solver() {
  SolverRegistry::add({"clique",
                       "CliReg: exact maximum clique (bitset branch and bound, colouring bound, "
                       "k-core pruning) on the pairwise-distance graph, then least-squares fit",
                       [] { return std::make_unique<CliqueSolver>(); }});
}

}  // namespace verifybench
