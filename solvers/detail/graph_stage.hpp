#pragma once
// The graph stage shared by the graph-based solvers (clique-*, mac): Eq. (1) with the solver's
// parameters, timed into result.times.graph_ms, its edge count into result.counters.graph_edges.
#include "core/timer.hpp"
#include "graph/compatibility_graph.hpp"
#include "solvers/solver.hpp"

namespace verifybench {

template <int Dim>
BitGraph build_graph_stage(const Correspondences<Dim>& corr, const SolverParams& params,
                           Result<Dim>& result) {
  StopWatch clock;
  BitGraph graph = build_compatibility_graph(
      corr, GraphParams{params.eps, params.max_graph_bytes, params.threads});
  result.times.graph_ms = clock.ms();
  result.counters.graph_edges = graph.edge_count();
  return graph;
}

}  // namespace verifybench
