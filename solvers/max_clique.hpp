#pragma once
// Exact maximum clique by bitset branch and bound with a greedy colouring bound (BBMC, San Segundo
// et al. 2011), after k-core pruning seeded by a greedy clique (as PMC does inside TEASER++).
#include <limits>
#include <vector>

#include "core/bitgraph.hpp"

namespace verifybench {

struct CliqueSearchParams {
  double time_limit_s = std::numeric_limits<double>::infinity();  ///< wall-clock limit
  long long node_limit = 0;  ///< branch nodes before giving up; 0 = no limit
};

struct CliqueSearchResult {
  std::vector<int> clique;  ///< vertex ids, ascending; the best found so far when !optimal
  bool optimal = false;     ///< the search finished, so clique is maximum
  long long nodes = 0;      ///< branch-and-bound nodes expanded
  int upper_bound = 0;      ///< degeneracy + 1, a bound on the clique number
};

CliqueSearchResult max_clique(const BitGraph& g, const CliqueSearchParams& params = {});

/// Core numbers (Batagelj & Zaversnik 2003) and the smallest-last removal order.
struct CoreDecomposition {
  std::vector<int> core;   ///< core number per vertex
  std::vector<int> order;  ///< vertices in removal order (non-decreasing core)
};
CoreDecomposition core_decomposition(const BitGraph& g);

}  // namespace verifybench
