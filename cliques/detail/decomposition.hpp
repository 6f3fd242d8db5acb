// The degeneracy decomposition: bbmc-dec, and auto's hand-off of long sparse searches
// (cliques/decomposition.cpp).
#pragma once

#include <algorithm>
#include <vector>

#include "cliques/detail/bbmc.hpp"
#include "cliques/detail/sat_bb.hpp"
#include "cliques/max_clique.hpp"

namespace verifybench::detail {

inline int max_core(const CoreDecomposition& cd) {
  return cd.core.empty() ? -1 : *std::max_element(cd.core.begin(), cd.core.end());
}

/// The vertices of `g` left after peeling, again and again, those of degree below k (ascending).
std::vector<int> k_core_of(const BitGraph& g, int k, SteadyClock::time_point deadline);

/// The subgraph of g on `members` (ascending ids) peeled to the k-core a clique larger than
/// `target` needs (k = target): `members` keeps the vertices left, vertex k of the result being
/// members[k]. `mask` is a zeroed scratch bitset of g.words() words, zeroed again on return.
/// Throws DeadlinePassed past `deadline`.
BitGraph core_subgraph(const BitGraph& g, std::vector<int>& members, int target,
                       std::vector<Word>& mask, SteadyClock::time_point deadline);

/// A local search on the same graph run between the decomposition's subproblems, as
/// BranchAndBound::interleave() runs it between nodes: to `initial_work` plus `share` times the
/// words the subproblems' searches have touched colouring.
struct Interleaved {
  LocalSearch* search = nullptr;
  long long initial_work = 0;
  double share = 0;
};

/// The search in each neighbourhood of the decomposition: BBMC (bbmc-dec), the MaxSAT bound
/// (SatBranchAndBound, LMC's bound) or, on near-cliques, the LP bound of the complement first and
/// BBMCX handing near-clique nodes to the cover search where it does not rule the neighbourhood
/// out. kMaxSatCover: the MaxSAT bound, but a neighbourhood that is itself a near-clique
/// (BranchAndBound::near_clique() on its members and the clique it needs) takes kCover's search;
/// each neighbourhood that needs 32 or more is first recoloured (recolours_within()), and one with
/// fewer members than 9/4 of the clique it needs hands its MaxSAT search to kCover's after 5,000
/// nodes (that MaxSAT search relabels its graph in the graph's own min-width order first); the
/// others reduce to the complement's kernel (CliqueKernel, cliques/detail/kernel.hpp), whose
/// MaxSAT search (in its own order) hands over after 5,000 nodes to the kernel's own
/// decomposition, with kMaxSatCover in its neighbourhoods, at most kMaxNesting levels down.
enum class Neighbourhood { kBbmc, kMaxSat, kCover, kMaxSatCover };

/// kMaxSatCover: how many times a kernel may be decomposed again below the first decomposition;
/// past that its MaxSAT search runs to the end. The kernels shrink at each level (b112_72 FPFH
/// 0.5 k10: 1,080, then 850, then 500 members; BENCHMARK.md, section 70): this bounds the stack.
constexpr int kMaxNesting = 8;

/// kMaxSatCover: the MaxSAT nodes after which a search hands over. A neighbourhood under 9/4 x the
/// clique it needs, but no near-clique, goes to kCover's search (b125_0 FPFH 0.3 k3: three of
/// 326,000-764,000 nodes, 40 s of 58; BENCHMARK.md, section 64); a kernel past that band, to its
/// own decomposition (section 70).
constexpr long long kSatNodesBeforeHandOver = 5000;

/// The largest clique above `incumbent` (ids of g) by the decomposition with `search` in each
/// neighbourhood (kMaxSat, and kMaxSatCover's neighbourhoods that are no near-cliques:
/// SatBranchAndBound with `options`, handed over after `sat_nodes_before_hand_over` nodes where
/// kMaxSatCover says, 0: never; a kernel decomposed again at most `nesting` levels down, 0: never),
/// or empty; budget.stopped when the budget ran out first.
std::vector<int> decompose(const BitGraph& g, int incumbent, SearchBudget& budget,
                           const Interleaved& helper = {}, SatOptions options = {},
                           Neighbourhood search = Neighbourhood::kMaxSat,
                           long long sat_nodes_before_hand_over = kSatNodesBeforeHandOver,
                           int nesting = kMaxNesting);

/// bbmc-dec: BBMC on each vertex's later neighbours in degeneracy order (PMC's scheme).
CliqueSearchResult run_bbmc_dec(const BitGraph& g, const CliqueSearchParams& p);

}  // namespace verifybench::detail
