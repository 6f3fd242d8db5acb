#pragma once
// Maximum clique algorithms on bitset graphs, registered by name so that the correspondence
// solvers, the DIMACS mode and the benchmarks all run the same code:
//   bbmc        BBMC (San Segundo et al. 2011): bitset branch and bound, greedy colouring bound,
//               min-width initial order; exact
//   bbmcr       bbmc with re-colouring of branching candidates (Re-NUMBER; BBMCR)
//   bbmc-kcore  bbmc after a greedy lower bound and k-core pruning (as PMC does inside TEASER++)
//   bbmcx       bbmcr plus the infra-chromatic bound of BBMCX
//   bbmcx-sat   bbmcr plus the incremental MaxSAT bound (IncMaxCLQ / MoMC: unit propagation and
//               failed literals over the colour classes; cliques/detail/sat_bb.hpp)
//   bbmcx-ls    bbmcx with a DLS-MC local search interleaved, for an early lower bound
//   bbmc-dec    PMC-style decomposition: for each vertex in degeneracy order, BBMC on its later
//               neighbours (a compact subgraph of at most degeneracy vertices); exact; parallel
//               with the same clique for any thread count
//   doll        Ostergard's Russian doll search (cliquer's algorithm) on bitsets; exact
//               (doll.cpp)
//   greedy      the greedy clique alone: no optimality proof (to show what exactness buys)
//   cliquer, igraph  peers from Debian's libcliquer and libigraph (cliquer.cpp, igraph.cpp),
//   registered when built
#include <cstdint>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "graph/bitgraph.hpp"

namespace verifybench {

struct CliqueSearchParams {
  double time_limit_s = std::numeric_limits<double>::infinity();  ///< wall-clock limit
  long long node_limit = 0;  ///< branch nodes before giving up; 0 = no limit (per thread)
  int threads =
      1;  ///< bbmc-dec: worker threads (0 = all cores); the clique is the same for any count
  std::uint64_t seed = 1;  ///< bbmcx-ls: the local search's random stream
  /// auto, on a sparse graph that is no near-clique: the row words BBMCX may colour (nodes times
  /// the pruned graph's words, about 3 s on a 2-core VM; where the degrees spread wide, a fixed
  /// share per node instead) before it hands the search to the decomposition with the MaxSAT
  /// bound; 0 = never (cliques/bbmc_variants.cpp).
  long long decompose_after_words = 40'000'000;
};

struct CliqueSearchResult {
  std::vector<int> clique;  ///< vertex ids, ascending; the best found so far when !optimal
  bool optimal = false;     ///< proven maximum (an exact algorithm that finished)
  bool stopped = false;     ///< the time or node limit cut the search short
  long long nodes = 0;      ///< branch-and-bound nodes expanded
  int upper_bound = 0;  ///< a proven upper bound on the clique number (its size when optimal)
  long long local_search_steps = 0;  ///< bbmcx-ls, auto: steps of the local search
};

using CliqueAlgorithm =
    std::function<CliqueSearchResult(const BitGraph&, const CliqueSearchParams&)>;

struct CliqueAlgorithmInfo {
  std::string name;
  std::string description;
  bool exact = true;  ///< proves optimality when it finishes
  CliqueAlgorithm run;
  bool child_process = false;  ///< searches in a forked child (the library peers)
};

class CliqueAlgorithms {
 public:
  static void add(CliqueAlgorithmInfo info);  ///< throws std::logic_error on a duplicate name
  static const CliqueAlgorithmInfo& get(const std::string& name);  ///< throws std::invalid_argument
  static std::vector<CliqueAlgorithmInfo> list();                  ///< sorted by name
};

/// Registers bbmc, bbmcr, bbmc-kcore, bbmc-dec, greedy and the peers (idempotent).
void register_clique_algorithms();

/// The default exact algorithm (the one behind the `clique` solver).
inline constexpr const char* kDefaultCliqueAlgorithm = "auto";
CliqueSearchResult max_clique(const BitGraph& g, const CliqueSearchParams& params = {});

struct MaximalCliqueParams {
  int min_size = 1;           ///< report cliques this large or larger
  long long max_cliques = 0;  ///< stop after this many; 0 = all
  double time_limit_s = std::numeric_limits<double>::infinity();  ///< wall-clock limit
};

/// Calls report(clique) once for every maximal clique of at least min_size vertices (original ids,
/// its first vertex in degeneracy order first). Returns false when a limit cut the enumeration
/// short. `nodes`, when given, receives the Bron-Kerbosch nodes expanded.
bool for_each_maximal_clique(const BitGraph& g, const MaximalCliqueParams& params,
                             const std::function<void(const std::vector<int>&)>& report,
                             long long* nodes = nullptr);

/// Dynamic local search for a large clique (DLS-MC, Pullan & Hoos 2006): expansion and plateau
/// swaps guided by vertex penalties, restarts from the last vertex added. No optimality proof; a
/// lower bound for the exact searches. Deterministic for a given seed.
struct LocalSearchParams {
  long long max_steps = 100000;                  ///< additions, swaps and restarts in all
  int target = std::numeric_limits<int>::max();  ///< stop once a clique this large is found
  int penalty_delay = 2;  ///< cycles between penalty decreases (1 = no penalties)
  std::uint64_t seed = 1;
  double time_limit_s = std::numeric_limits<double>::infinity();
};
/// The largest clique met (ascending ids); `steps_used`, when given, receives the steps taken.
std::vector<int> local_search_clique(const BitGraph& g, const LocalSearchParams& params,
                                     long long* steps_used = nullptr);

/// Core numbers (Batagelj & Zaversnik 2003) and the smallest-last removal order.
struct CoreDecomposition {
  std::vector<int> core;   ///< core number per vertex
  std::vector<int> order;  ///< vertices in removal order (non-decreasing core)
};
CoreDecomposition core_decomposition(const BitGraph& g);

/// Greedy clique from each vertex that could beat the incumbent, highest core first, adding the
/// candidate of highest core number each step.
std::vector<int> greedy_clique(const BitGraph& g, const CoreDecomposition& cd);

}  // namespace verifybench
