#pragma once
// Graphs with a planted near-clique whose clique number is known without any clique search, for
// the tests (an oracle independent of cliques/) and the benchmarks (bench_clique). A near-clique K
// (k vertices, some of their pairs removed) plus outliers that see fewer than omega / 2 vertices,
// so that no clique through an outlier comes near omega; vertex ids are shuffled. Parameters out
// of range (k < 1, outliers < 0, block outside 1..32, a density outside [0, 1], hubs outside
// 0..min(k, 100)) throw std::invalid_argument naming the value.
#include <cstdint>

#include "graph/bitgraph.hpp"

namespace verifybench {

struct PlantedGraph {
  BitGraph g;
  int omega = 0;       ///< the clique number, from the construction
  double removed = 0;  ///< share of K's pairs that are not edges
};

/// K's non-edges lie inside random blocks of at most `block` (<= 24) vertices, each pair of a block
/// removed with probability `block_density`: omega is the sum of the blocks' independence numbers
/// in the complement (each by exhaustive recursion). Blocks of 24 cap the removed share near
/// 23 / k (0.5% at k = 500 for density 0.1).
PlantedGraph block_near_clique(int k, int outliers, int block, double block_density,
                               std::uint64_t seed);

/// 1-5% of K's pairs removed, most of them at `hubs` (<= 100) noisy vertices, as in a
/// correspondence graph where matches with large errors break many constraints and the rest break
/// a few. K = hubs S + blocks of 12; a pair of K is a non-edge only between two hubs (each of the
/// two draws it at 1/2: probability 3/4), a hub and any other vertex, or two vertices of one block
/// (probability 0.2). A clique of K
/// is a set I of hubs that is a clique plus, in every block, an independent set of the block's
/// complement among the vertices every hub of I sees, so
///   omega(K) = max over cliques I of S of  |I| + sum_b alpha_b(B_b minus the non-neighbours of I)
/// with alpha_b tabulated over all 2^12 subsets of a block by alpha(X) = max(alpha(X - v),
/// 1 + alpha(X - v - N(v))). Half the hubs break 20-60% of their pairs, half 0.1-5%
/// (log-uniform), so that some belong to the optimum and some do not. Removed share: about
/// 4.7% at (k, hubs) = (500, 50), 3.1% at (1000, 70), 1.0% at (3000, 70).
PlantedGraph hub_near_clique(int k, int hubs, int outliers, std::uint64_t seed);

}  // namespace verifybench
