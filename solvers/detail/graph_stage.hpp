#pragma once
// The graph stage shared by the graph-based solvers (clique-*, mac): Eq. (1) with the solver's
// parameters, timed into result.times.graph_ms, its edge count into result.counters.graph_edges.
#include <optional>

#include <algorithm>

#include "cliques/max_clique.hpp"
#include "core/timer.hpp"
#include "graph/compatibility_graph.hpp"
#include "solvers/solver.hpp"

namespace verifybench {

/// nullopt when the time limit passed during construction: `result` is then final (status
/// time_limit, nothing selected, not accepted).
template <int Dim>
std::optional<BitGraph> build_graph_stage(const Correspondences<Dim>& corr,
                                          const SolverParams& params, Result<Dim>& result,
                                          double eps) {
  StopWatch clock;
  try {
    BitGraph graph = build_compatibility_graph(
        corr, GraphParams{eps, params.max_graph_bytes, params.threads, params.time_limit_s});
    result.times.graph_ms = clock.ms();
    result.counters.graph_edges = graph.edge_count();
    return graph;
  } catch (const GraphTimeLimit& e) {
    result.times.graph_ms = clock.ms();
    result.status = Status::time_limit;
    result.accepted = false;
    result.message = e.what();
    return std::nullopt;
  }
}

template <int Dim>
std::optional<BitGraph> build_graph_stage(const Correspondences<Dim>& corr,
                                          const SolverParams& params, Result<Dim>& result) {
  return build_graph_stage(corr, params, result, params.eps);
}

/// omega(G) <= max core number + 1 of the Eq. (1) graph at `eps` (a clique of k vertices lies in
/// the (k - 1)-core): the score bound of the graph solvers (Solver::score_bound). nullopt when the
/// time limit passes while the graph is built.
template <int Dim>
std::optional<int> clique_number_bound(const Correspondences<Dim>& corr, const SolverParams& params,
                                       double eps) {
  try {
    const BitGraph graph = build_compatibility_graph(
        corr, GraphParams{eps, params.max_graph_bytes, params.threads, params.time_limit_s});
    const CoreDecomposition cd = core_decomposition(graph);
    return cd.core.empty() ? 0 : *std::max_element(cd.core.begin(), cd.core.end()) + 1;
  } catch (const GraphTimeLimit&) {
    return std::nullopt;
  }
}

/// The consensus of one rigid motion within `threshold` (residuals r_i, r_j < threshold) is a
/// clique of the Eq. (1) graph at 2 threshold: | ||m_i - m_j|| - ||q_i - q_j|| | <= r_i + r_j by
/// the triangle inequality. So the consensus solvers' (ransac, mac) score is bounded as the
/// clique's is, on that graph (widened by 1e-9 against rounding).
template <int Dim>
std::optional<int> consensus_bound(const Correspondences<Dim>& corr, const SolverParams& params) {
  return clique_number_bound(corr, params, 2.0 * params.inlier_threshold * (1.0 + 1e-9));
}

}  // namespace verifybench
