#pragma once
// The graph stage shared by the graph-based solvers (clique-*, mac, jcbb): Eq. (1) with the
// solver's parameters, timed into result.times.graph_ms, its edge count into
// result.counters.graph_edges; and the clique-number bound behind their score bounds.
#include <algorithm>
#include <optional>

#include "cliques/max_clique.hpp"
#include "core/timer.hpp"
#include "graph/compatibility_graph.hpp"
#include "graph/small_graph.hpp"
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
  } catch (const DeadlinePassed& e) {
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

/// Correspondences per part of clique_number_bound: parts of this size build in a few ms, and
/// their bounds add up to within 1-3% of the whole graph's on 25,000-correspondence k-NN nulls.
inline constexpr int kBoundPartSize = 2048;

/// An upper bound on omega of the Eq. (1) graph at `eps`, the score bound of the graph solvers
/// (Solver::score_bound): split the correspondences into parts (i mod parts), and add up a bound
/// of each part's clique number; a clique's vertices in one part are a clique of that part. Parts
/// of up to 64 are solved exactly on one word per row (small_graph.hpp: at parts of 64, 8-29%
/// below the cores' bound, and no allocation); larger ones are bounded by their max core
/// number + 1 (a clique of k vertices lies in the (k - 1)-core). The parts' graphs cost
/// n^2 / parts pair tests; on random-like graphs core numbers scale with the vertex count, so the
/// sum stays close to the whole graph's bound (BENCHMARK.md section 21: 541 ms -> 36 ms, bound
/// 747 -> 755, on a 25,000-correspondence null). nullopt when the time limit passes.
template <int Dim>
std::optional<int> clique_number_bound(const Correspondences<Dim>& corr, const SolverParams& params,
                                       double eps, int part_size = kBoundPartSize) {
  const int n = static_cast<int>(corr.size());
  const int parts = std::max(1, (n + part_size - 1) / part_size);
  int bound = 0;
  StopWatch clock;
  if (part_size <= SmallGraph::kMaxVertices) {  // every part has at most part_size members
    const auto deadline = deadline_after(params.time_limit_s);
    int index[SmallGraph::kMaxVertices];
    for (int q = 0; q < parts; ++q) {
      if ((q & 63) == 63 && SteadyClock::now() >= deadline) return std::nullopt;
      int size = 0;
      for (int i = q; i < n; i += parts) index[size++] = i;
      bound += small_clique_number(small_compatibility_graph(corr, index, size, eps));
    }
    return bound;
  }
  try {
    for (int q = 0; q < parts; ++q) {
      Correspondences<Dim> part;
      const int size = (n - q + parts - 1) / parts;
      part.source.resize(Dim, size);
      part.target.resize(Dim, size);
      for (int i = q, j = 0; i < n; i += parts, ++j) {
        part.source.col(j) = corr.source.col(i);
        part.target.col(j) = corr.target.col(i);
      }
      const BitGraph graph = build_compatibility_graph(
          part, GraphParams{eps, params.max_graph_bytes, params.threads,
                            params.time_limit_s - clock.ms() / 1000.0});
      const CoreDecomposition cd = core_decomposition(graph);
      if (!cd.core.empty()) bound += *std::max_element(cd.core.begin(), cd.core.end()) + 1;
    }
  } catch (const DeadlinePassed&) {
    return std::nullopt;
  }
  return bound;
}

/// The consensus of one rigid motion within `threshold` (residuals r_i, r_j < threshold) is a
/// clique of the Eq. (1) graph at 2 threshold: | ||m_i - m_j|| - ||q_i - q_j|| | <= r_i + r_j by
/// the triangle inequality. So the consensus solvers' (ransac, mac) score is bounded as the
/// clique's is, on that graph (widened by 1e-9 against rounding).
template <int Dim>
std::optional<int> consensus_bound(const Correspondences<Dim>& corr, const SolverParams& params,
                                   int part_size = kBoundPartSize) {
  return clique_number_bound(corr, params, 2.0 * params.inlier_threshold * (1.0 + 1e-9), part_size);
}

}  // namespace verifybench
