#pragma once
// The graph stage shared by the graph-based solvers (clique-*, mac): Eq. (1) with the solver's
// parameters, timed into result.times.graph_ms, its edge count into result.counters.graph_edges.
#include <optional>

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

}  // namespace verifybench
