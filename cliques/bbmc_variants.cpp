// Core decomposition, the greedy lower bound and the exact clique algorithms of max_clique.hpp.
#include <algorithm>
#include <cmath>
#include <memory>
#include <numeric>
#include <stdexcept>

#include "cliques/detail/bbmc.hpp"
#include "cliques/detail/cover.hpp"
#include "cliques/detail/decomposition.hpp"
#include "cliques/detail/sat_bb.hpp"
#include "cliques/max_clique.hpp"
#include "core/random.hpp"
#include "core/registry.hpp"

namespace verifybench {

using detail::BranchAndBound;
using detail::decompose;
using detail::k_core_of;
using detail::max_core;
using detail::run_bbmc_dec;
using detail::finish;
using detail::for_each_bit;
using detail::kBits;
using detail::make_budget;
using detail::SearchBudget;
using detail::Word;

std::vector<int> greedy_clique(const BitGraph& g, const CoreDecomposition& cd) {
  bool stopped = false;
  return detail::greedy_clique(g, cd, detail::kNoDeadline, stopped);
}

// A greedy start that sees at least 1/kDenseStart of the vertices picks through the core order.
constexpr int kDenseStart = 8;

std::vector<int> detail::greedy_clique(const BitGraph& g, const CoreDecomposition& cd,
                                       SteadyClock::time_point deadline, bool& stopped,
                                       int max_starts) {
  const int W = g.words();
  int starts = 0;
  std::vector<int> best, clique;
  std::vector<Word> cand(static_cast<std::size_t>(W));
  // Each step adds the candidate of highest core number (the lowest id among equals). From a
  // start that sees few vertices, by scanning the candidates; from one that sees many (a
  // near-clique), as the first vertex of `by_core` still a candidate: candidates only leave, so
  // the scan never goes back, one pass over the vertices per start instead of a scan of every
  // candidate per vertex added (which took 14 s for all the starts of a 4,500-vertex near-clique).
  std::vector<int> by_core;  // all vertices, highest core first, ties by id; made when needed
  auto highest_core = [&](int u, int pick) {
    return pick < 0 ||
           cd.core[static_cast<std::size_t>(u)] > cd.core[static_cast<std::size_t>(pick)];
  };
  for (auto it = cd.order.rbegin(); it != cd.order.rend(); ++it) {
    const int v = *it;
    if (cd.core[v] + 1 <= static_cast<int>(best.size())) continue;
    if (starts++ == max_starts) break;
    clique.assign(1, v);
    std::copy(g.row(v), g.row(v) + W, cand.begin());
    const bool dense = static_cast<long long>(kDenseStart) * g.degree(v) >= g.size();
    if (dense && by_core.empty()) {
      by_core.resize(static_cast<std::size_t>(g.size()));
      std::iota(by_core.begin(), by_core.end(), 0);
      std::stable_sort(by_core.begin(), by_core.end(),
                       [&](int a, int b) { return highest_core(a, b); });
    }
    std::size_t at = 0;
    for (;;) {
      int pick = -1;
      if (dense) {
        while (
            at < by_core.size() &&
            !((cand[static_cast<std::size_t>(by_core[at] / kBits)] >> (by_core[at] % kBits)) & 1)) {
          ++at;
        }
        if (at < by_core.size()) pick = by_core[at];
      } else {
        for_each_bit(cand.data(), W, [&](int u) {
          if (highest_core(u, pick)) pick = u;
        });
      }
      if (pick < 0) break;
      clique.push_back(pick);
      const Word* row = g.row(pick);
      for (int w = 0; w < W; ++w) cand[w] &= row[w];
      if ((clique.size() & 63) == 0 && SteadyClock::now() >= deadline) {
        stopped = true;  // a partial greedy clique is still a clique
        break;
      }
    }
    if (clique.size() > best.size()) best = clique;
    if (stopped || SteadyClock::now() >= deadline) {
      stopped = true;
      break;
    }
  }
  return best;
}

CoreDecomposition core_decomposition(const BitGraph& g) {
  return detail::core_decomposition(g, detail::kNoDeadline);
}

CoreDecomposition detail::core_decomposition(const BitGraph& g, SteadyClock::time_point deadline) {
  const int n = g.size();
  CoreDecomposition cd;
  std::vector<int> deg(static_cast<std::size_t>(n)), pos(static_cast<std::size_t>(n)),
      vert(static_cast<std::size_t>(n));
  int max_deg = 0;
  for (int v = 0; v < n; ++v) {
    if ((v & 1023) == 1023) throw_if_past(deadline);
    max_deg = std::max(max_deg, deg[v] = g.degree(v));
  }
  std::vector<int> bin(static_cast<std::size_t>(max_deg) + 1, 0);
  for (int v = 0; v < n; ++v) ++bin[deg[v]];
  for (int d = 0, start = 0; d <= max_deg; ++d) {
    const int c = bin[d];
    bin[d] = start;
    start += c;
  }
  for (int v = 0; v < n; ++v) {
    pos[v] = bin[deg[v]]++;
    vert[pos[v]] = v;
  }
  for (int d = max_deg; d > 0; --d) bin[d] = bin[d - 1];
  bin[0] = 0;
  // Only neighbours not removed yet can lose degree: scan row(v) & alive, which halves the visits.
  const int W = g.words();
  std::vector<Word> alive = detail::first_n_set(n, W);
  for (int i = 0; i < n; ++i) {
    if ((i & 255) == 255) throw_if_past(deadline);
    const int v = vert[i];
    alive[static_cast<std::size_t>(v / kBits)] &= ~(Word{1} << (v % kBits));
    const Word* row = g.row(v);
    for (int w = 0; w < W; ++w) {
      for (Word x = row[w] & alive[static_cast<std::size_t>(w)]; x; x &= x - 1) {
        const int u = w * kBits + detail::lowest_bit(x);
        if (deg[u] <= deg[v]) continue;
        // Move u to the front of its degree bucket, then shrink the bucket (Batagelj-Zaversnik).
        const int du = deg[u], pu = pos[u], pf = bin[du], first = vert[pf];
        if (u != first) {
          std::swap(vert[pu], vert[pf]);
          pos[u] = pf;
          pos[first] = pu;
        }
        ++bin[du];
        --deg[u];
      }
    }
  }
  cd.core = std::move(deg);
  cd.order = std::move(vert);
  return cd;
}

namespace {

// The interleaved local search (bbmcx-ls): 100 n visits up front (a few hundred steps), then a
// tenth of the colouring's words: some more time where it finds nothing better (johnson16-2-4,
// p_hat1000-1), an early incumbent on brock400_4 (shares measured in BENCHMARK.md, section 5c).
constexpr long long kLocalInitialVisitsPerVertex = 100;
constexpr double kLocalShare = 0.1;
constexpr std::uint64_t kLocalSearchStream = 0x15;


/// BBMC on the subgraph induced by `vertices` (in that order, which is the initial colouring
/// order); returns a clique larger than `incumbent` in original ids, or an empty vector.
/// With `local_search`, a DLS-MC search runs interleaved (BranchAndBound::interleave).
std::vector<int> search_ordered(const BitGraph& g, const std::vector<int>& vertices, int incumbent,
                                SearchBudget& budget, bool recolour = false, bool infra = false,
                                const LocalSearchParams* local_search = nullptr,
                                long long* local_steps = nullptr) {
  const BitGraph sub = detail::permuted(g, vertices, budget.deadline);
  BranchAndBound bb(sub, incumbent, budget, recolour, infra);
  std::unique_ptr<LocalSearch> helper;
  if (local_search) {
    helper = std::make_unique<LocalSearch>(sub, *local_search);
    bb.interleave(helper.get(), kLocalInitialVisitsPerVertex * sub.size(), kLocalShare);
  }
  bb.run();
  if (helper && local_steps) *local_steps = helper->steps();
  std::vector<int> found;
  for (int k : bb.best()) found.push_back(vertices[static_cast<std::size_t>(k)]);
  return found;
}

// bbmc / bbmcr / bbmcx: the whole graph in min-width order (highest core first), no pre-pruning.
template <bool kRecolour, bool kInfra = false>
CliqueSearchResult run_bbmc(const BitGraph& g, const CliqueSearchParams& p) {
  SearchBudget budget = make_budget(p);
  const CoreDecomposition cd = detail::core_decomposition(g, budget.deadline);
  const std::vector<int> order(cd.order.rbegin(), cd.order.rend());
  return finish(search_ordered(g, order, 0, budget, kRecolour, kInfra), true, budget,
                max_core(cd) + 1);
}

// bbmcx-sat: the whole graph in min-width order, the incremental MaxSAT bound (sat_bb.hpp).
CliqueSearchResult run_bbmcx_sat(const BitGraph& g, const CliqueSearchParams& p) {
  SearchBudget budget = make_budget(p);
  const CoreDecomposition cd = detail::core_decomposition(g, budget.deadline);
  const std::vector<int> order(cd.order.rbegin(), cd.order.rend());
  const BitGraph sub = detail::permuted(g, order, budget.deadline);
  detail::SatBranchAndBound bb(sub, 0, budget);
  bb.run();
  std::vector<int> found;
  for (int k : bb.best()) found.push_back(order[static_cast<std::size_t>(k)]);
  return finish(std::move(found), true, budget, max_core(cd) + 1);
}

// bbmcx-ls: bbmcx with DLS-MC interleaved; its stream derives from the seed, so a seed gives one
// clique and one search tree.
CliqueSearchResult run_bbmcx_ls(const BitGraph& g, const CliqueSearchParams& p) {
  SearchBudget budget = make_budget(p);
  const CoreDecomposition cd = detail::core_decomposition(g, budget.deadline);
  const std::vector<int> order(cd.order.rbegin(), cd.order.rend());
  LocalSearchParams ls;
  ls.target = max_core(cd) + 1;
  ls.seed = derive_seed(p.seed, {kLocalSearchStream});
  long long steps = 0;
  CliqueSearchResult r =
      finish(search_ordered(g, order, 0, budget, true, true, &ls, &steps), true, budget, ls.target);
  r.local_search_steps = steps;
  return r;
}

// bbmc-kcore: greedy lower bound, drop vertices whose core number cannot beat it, BBMC on the rest.
CliqueSearchResult run_bbmc_kcore(const BitGraph& g, const CliqueSearchParams& p) {
  SearchBudget budget = make_budget(p);
  const CoreDecomposition cd = detail::core_decomposition(g, budget.deadline);
  const int upper = max_core(cd) + 1;
  std::vector<int> best = detail::greedy_clique(g, cd, budget.deadline, budget.stopped);
  if (budget.stopped) return finish(std::move(best), true, budget, upper);
  const int incumbent = static_cast<int>(best.size());
  if (incumbent < upper) {
    std::vector<int> kept;  // a clique larger than the incumbent lies in the incumbent-core
    for (auto it = cd.order.rbegin(); it != cd.order.rend(); ++it) {
      if (cd.core[static_cast<std::size_t>(*it)] >= incumbent) kept.push_back(*it);
    }
    std::vector<int> found = search_ordered(g, kept, incumbent, budget);
    if (!found.empty()) best = std::move(found);
  }
  return finish(std::move(best), true, budget, upper);
}

// The near-clique path (cover, auto): a lower bound from a few greedy starts, then only the
// vertices whose core number could beat it (a clique larger than k lies in the k-core).
constexpr int kGreedyStarts = 8;

struct Pruned {
  CoreDecomposition cd;
  int upper = 0;          // max core + 1
  std::vector<int> best;  // the greedy clique
  std::vector<int> kept;  // core >= |best|, highest core first
};

Pruned prune_by_greedy(const BitGraph& g, SearchBudget& budget) {
  Pruned p;
  p.cd = detail::core_decomposition(g, budget.deadline);
  p.upper = max_core(p.cd) + 1;
  p.best = detail::greedy_clique(g, p.cd, budget.deadline, budget.stopped, kGreedyStarts);
  const int incumbent = static_cast<int>(p.best.size());
  for (auto it = p.cd.order.rbegin(); it != p.cd.order.rend(); ++it) {
    if (p.cd.core[static_cast<std::size_t>(*it)] >= incumbent) p.kept.push_back(*it);
  }
  return p;
}

// The local search on the pruned graph: a base plus twice the greedy clique (it adds one vertex a
// step, so it needs more steps than the clique it is to reach has vertices).
constexpr long long kLocalBaseSteps = 4000;
constexpr int kNearCliqueRatio = 8;  // the greedy clique is at least 1/8 of the pruned graph
// On sparse graphs (density under kDenseGraph) the local search runs up front from 1/12, and the
// graph is searched as a near-clique when the clique it finds reaches 1/8: the lidar_pair FPFH
// 0.3 k10 dump (greedy 1,480 of 14,710 pruned; 2,604 after the local search) reaches 2,733 at
// 30 s rather than 2,047; no other corpus, DIMACS or G(n, p) graph falls between 1/12 and 1/8
// (BENCHMARK.md, section 56).
constexpr int kWideLocalRatio = 12;
long long local_steps(int greedy) { return kLocalBaseSteps + 2LL * greedy; }
// auto hands near-clique nodes to the cover search on sparse graphs (the correspondence graphs:
// 3DMatch at density 0.07, omega 60, 15% more instructions without it), and on dense ones only
// when the incumbent is this large.
constexpr int kCoverIncumbent = 64;
constexpr double kDenseGraph = 0.5;
// On graphs at least this dense auto searches with the MaxSAT bound (bbmcx-sat, sat_bb.hpp): its
// propagation walks each unit's non-neighbours, so it costs per node what the complement holds.
// On G(n, p) at n = 100-200 (near-cliques by auto's measure, so the local search runs up front) it
// costs 0.66-1.03x what BBMCX does at p = 0.85-0.875 (C125.9, 0.90: 0.63x) and 1.2-1.5x at
// 0.75-0.8 (BENCHMARK.md, section 45). Correspondence graphs are far sparser.
constexpr double kMaxSatDensity = 0.85;
// There the interleaved local search takes this share of the colouring's words: at a tenth (the
// other paths' kLocalShare) the MaxSAT search, whose nodes cost more than their colouring says,
// spends 4-5% more where the search up front already holds omega; at a twentieth 0-3%.
constexpr double kDenseLocalShare = 0.05;
constexpr std::uint64_t kInterleavedStream = 1;
// On dense graphs the MaxSAT test goes without Re-NUMBER and failed literals (sat_bb.hpp); from
// kMaxSatDensity it relaxes the inconsistent subsets it finds rather than freezing them, which
// the dense path's decomposition neighbourhoods (density 0.6-0.75) do not repay (BENCHMARK.md,
// section 56).
constexpr detail::SatOptions kDenseSat{false, false, true};
// Where the clique is at least a third of the pruned graph (the complement's kernels that
// correspondence graphs' neighbourhoods reduce to: 36-48%), the MaxSAT tree hands over to the
// degeneracy decomposition after kSatNodesBeforeHandOver nodes, as the hand-off's kernels do: an
// 871-vertex kernel at density 0.936 (omega 336) unproved at 20 s -> 0.77 s, three others
// 1.6-5x faster. G(n, p) at 0.9-0.97, whose cliques are 20-25% of the vertices, keep the one tree
// (G(200, 0.9) took 1.15x with the hand-over; BENCHMARK.md, section 70).
constexpr int kLargeCliqueShare = 3;
constexpr detail::SatOptions kNeighbourhoodSat{false, false, false};
// In the hand-off of long sparse searches the neighbourhoods keep Re-NUMBER and failed literals,
// and below kDispersedDensity (the correspondence graphs of scans, whose neighbourhoods hold
// cliques of 100-600) relax the inconsistent subsets too: balm_realworld's b148_51 FPFH 0.5 k3
// 4.1 -> 1.9 s (2.2x fewer nodes), the corpus's k00_198_94 0.5 k10 5.1 -> 4.5 s, 0.5 k3 and
// b112_72 0.5 k3 0.96-0.99x; on p_hat500-1 and p_hat1000-1 (density 0.25, omega 9-10) it cost
// 1.12-1.16x (BENCHMARK.md, section 63).
constexpr detail::SatOptions kSparseNeighbourhoodSat{true, true, true};
double density(const BitGraph& g) {
  const double n = g.size();
  return n > 1 ? 2.0 * static_cast<double>(g.edge_count()) / (n * (n - 1)) : 0.0;
}
// The spread of the degrees against a random graph's of the same density: their standard
// deviation over that of Binomial(n - 1, density). About 1 on G(n, p) and on DIMACS's random-like
// families (brock, sanr, san: 0.8-1.0; keller4 1.2; hamming, johnson: 0); 2.4-3.6 where each
// vertex has its own density, as in the p_hat generator's graphs (p_hat300-3: 3.0).
double degree_dispersion(const BitGraph& g) {
  const int n = g.size();
  if (n < 3) return 0.0;
  double sum = 0, sq = 0;
  for (int v = 0; v < n; ++v) {
    const double d = BitGraph::count(g.row(v), g.words());
    sum += d;
    sq += d * d;
  }
  const double mean = sum / n, p = mean / (n - 1);
  const double binomial = (n - 1) * p * (1 - p);
  return binomial > 0 ? std::sqrt(std::max(0.0, sq / n - mean * mean) / binomial) : 0.0;
}
// On a dense graph that is no near-clique, auto searches with the degeneracy decomposition and
// the MaxSAT bound in each neighbourhood, bbmcx-ls's local search run between the subproblems,
// unless the graph is regular (its degrees spread less than this): p_hat300-3 195 -> 142 ms and the
// p_hat generator's graphs 0.66-0.87x (section 46), and, since the MaxSAT test's colour groups,
// G(n, p) at p 0.6-0.8 0.54-0.94x, brock200_1 0.75x, sanr200_0.7 0.75x, san200_0.7_1 0.61x (in
// instructions; brock400_4 and keller4 1.19x). On regular graphs the MaxSAT bound saves the
// fewest nodes for its cost (johnson16-2-4 1.51x, hamming8-4 0.80x): BBMCX keeps them
// (BENCHMARK.md, section 49).
constexpr double kIrregular = 0.5;
// From kDispersedDensity to kDenseGraph, on graphs that are no near-clique and whose degrees spread
// at least twice as wide as a random graph's (the p_hat generator's scheme: dispersion 2.3-7.7 at
// density 0.24-0.5), BBMCX hands the search to the decomposition after decompose_after_words /
// kDispersedWordsPerNode nodes (2,000 by default) rather than after that many row words: the long
// searches take 0.12-0.91x the time (a p_hat500-2-like graph 476 -> 59 ms, p_hat1000-1 103 -> 93),
// and the easy correspondence-like graphs of that density (uniform outliers, eps a tenth of the
// scene) end in BBMCX before it as they did; going to the decomposition at once cost those
// 1.2-3x, and at density 0.1-0.15 it mostly loses (BENCHMARK.md, section 50).
constexpr double kDispersedDensity = 0.2;
constexpr double kDispersed = 2.0;
constexpr long long kDispersedWordsPerNode = 20'000;
// Under kDispersedDensity the same hand-off comes after decompose_after_words /
// kSparseDispersedWordsPerNode nodes (5,000 by default) where the degrees spread that wide: the
// correspondence graphs of real scans (dispersion 2.5-31 on the corpus's and balm_realworld's
// sparse dumps). After that many row words instead, a node's cost was misjudged where it colours
// thousands of candidates or runs the cover search (balm_realworld's FPFH k1 dumps: 500,000
// nodes, 30-45 s, before the hand-off; the decomposition at once proves them in 76 ms-1.7 s).
// The corpus's short BBMCX proofs on this path take at most 4,690 nodes (corr_6614, the B-SHOT
// and k1 dumps) and keep them; its two long ones (k00_198_94 0.3 k3 and k10, 39,360 and 64,638
// nodes) are handed over and take 1.3-2x as long, still ahead of every peer (section 62).
constexpr long long kSparseDispersedWordsPerNode = 8'000;
// From this density up, dispersed graphs take the dense graphs' path (the decomposition at once,
// the interleaved local search, the dense MaxSAT options): the p_hat scheme's graphs of density
// 0.49-0.5 (p_hat300-2, p_hat700-2 and p_hat1000-2 are 0.49-0.50) 0.66-0.77x the time of the
// hand-off after 2,000 nodes; at 0.42-0.44 it is 0.83-2.1x, worst on the easy correspondence-like
// graphs (BENCHMARK.md, section 53).
constexpr double kDispersedDense = 0.45;
bool decomposes(const BitGraph& g, double graph_density) {
  if (graph_density < kDispersedDense) return false;
  const double dispersion = degree_dispersion(g);
  return dispersion >= (graph_density >= kDenseGraph ? kIrregular : kDispersed);
}
bool hands_off_near_cliques(double graph_density, int incumbent) {
  return incumbent >= kCoverIncumbent || graph_density < kDenseGraph;
}

// A near-clique whose clique is under half the pruned graph (the corpus's k-NN dumps: k3 and k10
// FPFH matches, cliques of 1,200-6,100 among 3,600-14,000 vertices) is out of the cover search's
// reach at BBMCX's root, whose colouring bound is 40-70% above omega there. BBMCX proves some in a
// hundred nodes (k00_199_198 and k00_95_94 0.3 k3: 99 and 103) and none of the k10 ones in 30 s
// (3,800-36,000 nodes); after kWideNearCliqueNodes nodes it hands the search to the decomposition
// whose neighbourhoods, near-cliques under the degeneracy, the complement's LP bound rules out
// one by one (2,300 of 2,500 on k08_1500_720 0.3 k10). The corpus: 10 -> 2 graphs unproved in 30
// s, the k3 dumps 0.3-1.7 s slower to 5-15x faster (BENCHMARK.md, section 51).
constexpr long long kWideNearCliqueNodes = 256;

// On a sparse graph that is no near-clique, auto's BBMCX colours the whole pruned graph at each
// node, and its classes mix far-apart regions. Past params.decompose_after_words of rows coloured
// (nodes times the pruned graph's words) it hands the search to the decomposition of bbmc-dec with
// the MaxSAT bound in each neighbourhood (LMC's scheme), from its incumbent. On the corpus every
// sparse search BBMCX proves stays under 2.8e7 (k00_198_94 0.3 k10: 71,401 nodes of 391 words,
// 2.4 s), and the two it does not prove in 30 s (k00_198_94 0.5 k3/k10, omega 120 and 110) are
// proved in 6.4 and 8.7 s this way; the DIMACS graphs never get there (BENCHMARK.md, section 43).
// Those dumps' degrees spread wide, so since section 62 they are handed over after 5,000 nodes
// (kSparseDispersedWordsPerNode: 0.5 k3/k10 in 3.4 and 5.3 s). A neighbourhood of that
// decomposition that is itself a near-clique takes the cover search (kMaxSatCover): k3 dumps of
// scans that overlap well hold dense clusters (balm_realworld's b125_0 FPFH 0.5 k3: neighbourhoods
// of 585-800 members that need 529-580; it and b176_114 0.3 k3, unproved in 30 s, in 2.5 and
// 7.3 s; section 63). Each neighbourhood that needs 32 or more is first recoloured (iterated
// greedy), and just past the near-clique ratio the MaxSAT search hands over to the cover search
// after 5,000 nodes: three more of balm's k3/k10 dumps proved in 11-21 s (section 64).

template <bool kAuto>
CliqueSearchResult run_pruned(const BitGraph& g, const CliqueSearchParams& params) {
  SearchBudget budget = make_budget(params);
  Pruned p = prune_by_greedy(g, budget);
  int upper = p.upper;
  int incumbent = static_cast<int>(p.best.size());
  long long ls_steps = 0;  // the local search's, up front or interleaved
  // Past the deadline, set-up steps throw DeadlinePassed: the incumbent is kept, status time_limit.
  if (!budget.stopped && static_cast<int>(p.kept.size()) > incumbent && incumbent < upper) try {
      BitGraph sub = detail::permuted(g, p.kept, budget.deadline);
      // A local search on the pruned graph usually beats the greedy starts by 5-30% on
      // near-cliques; the core of the larger incumbent is then smaller.
      LocalSearchParams ls;
      ls.max_steps = local_steps(incumbent);
      ls.seed = derive_seed(params.seed, {kLocalSearchStream});
      ls.time_limit_s = seconds_until(budget.deadline);
      // The whole graph's density, before pruning (one pass over its rows).
      const double dens = kAuto ? density(g) : 0.0;
      // Only where the pruned graph is a near-clique: a sparse graph's small cliques are found by
      // the search at once, and there each step would cost a scan of thousands of non-neighbours.
      bool near_clique = static_cast<long long>(incumbent) * kNearCliqueRatio >= sub.size();
      const bool wide_sparse = kAuto && dens < kDenseGraph &&
                               static_cast<long long>(incumbent) * kWideLocalRatio >= sub.size();
      // Where a greedy colouring already bounds the cliques by the incumbent, it is the answer:
      // neither the local search (4,000 steps and more, 1-2 ms) nor the search runs
      // (hamming6-2, hamming8-2; BENCHMARK.md, section 58).
      const bool searched_up_front = near_clique || wide_sparse;
      const bool proved = searched_up_front && detail::colours_within(sub, incumbent);
      std::vector<int> local;
      if (searched_up_front && !proved) {
        local = local_search_clique(sub, ls, &ls_steps);
      }
      if (static_cast<int>(local.size()) > incumbent) {
        p.best.clear();
        for (int k : local) p.best.push_back(p.kept[static_cast<std::size_t>(k)]);
        incumbent = static_cast<int>(p.best.size());
        std::vector<int> core = k_core_of(sub, incumbent, budget.deadline);
        std::vector<int> kept;
        for (int k : core) kept.push_back(p.kept[static_cast<std::size_t>(k)]);
        p.kept = std::move(kept);
        sub = detail::permuted(g, p.kept, budget.deadline);
      }
      // A wide graph whose local search took it to a near-clique is searched as one.
      if (wide_sparse) {
        near_clique = static_cast<long long>(incumbent) * kNearCliqueRatio >= sub.size();
      }
      std::vector<int> found;
      if (proved || sub.size() <= incumbent) {
        upper = std::min(upper, incumbent);
      } else if (!kAuto) {
        detail::CoverSearch cover(sub, incumbent, budget);
        cover.run();
        found = cover.best();
        upper = std::min(upper, cover.upper_bound());
      } else if (dens >= kMaxSatDensity) {
        detail::SatBranchAndBound bb(sub, incumbent, budget, kDenseSat);
        if (hands_off_near_cliques(dens, incumbent)) {
          bb.hand_off_near_cliques(BranchAndBound::kMinCover);
        }
        // The local search up front (on near-cliques) misses omega on some of these graphs
        // (G(200, 0.9) s1 holds 39 of 40 until 2 s into a 5 s search): one on a stream of its own
        // runs interleaved at a twentieth of the colouring's words (gnp200_0.9_s1 923,255 ->
        // 717,504 nodes; BENCHMARK.md, section 61); on the other graphs it is the only one.
        LocalSearchParams interleaved = ls;
        interleaved.max_steps = LocalSearchParams{}.max_steps;
        interleaved.target = upper;
        interleaved.seed = derive_seed(params.seed, {kLocalSearchStream, kInterleavedStream});
        LocalSearch helper(sub, interleaved);
        bb.interleave(&helper, kLocalInitialVisitsPerVertex * sub.size(), kDenseLocalShare);
        const bool large_clique =
            params.decompose_after_words > 0 && kLargeCliqueShare * incumbent >= sub.size();
        const bool hand_over = detail::run_capped(
            budget, large_clique ? detail::kSatNodesBeforeHandOver : 0, [&] { bb.run(); });
        found = bb.best();
        ls_steps += helper.steps();
        // Stopped by its own cap (not the caller's limits, nor the deadline): the decomposition.
        if (hand_over) {
          const int size = std::max(incumbent, static_cast<int>(found.size()));
          try {  // a deadline in its set-up keeps the tree's clique
            std::vector<int> better =
                decompose(sub, size, budget, {}, {}, detail::Neighbourhood::kMaxSatCover);
            if (!better.empty()) found = std::move(better);
          } catch (const DeadlinePassed&) {
            budget.stopped = true;
          }
        }
      } else if (!near_clique && decomposes(g, dens)) {
        LocalSearchParams interleaved = ls;
        interleaved.max_steps = LocalSearchParams{}.max_steps;
        interleaved.target = upper;
        LocalSearch helper(sub, interleaved);
        found = decompose(sub, incumbent, budget,
                          {&helper, kLocalInitialVisitsPerVertex * sub.size(), kLocalShare},
                          kNeighbourhoodSat);
        ls_steps += helper.steps();
      } else {
        BranchAndBound bb(sub, incumbent, budget, true, true);
        // The cover hand-off pays on near-cliques whose cliques run to hundreds (the corpus) and
        // on sparse correspondence graphs; on dense graphs with smaller cliques it costs (C125.9
        // 339 -> 25 ms, p_hat300-3 7.7 -> 0.61 s, gen200_p0.9_55 29 -> 4 ms without it;
        // BENCHMARK.md, section 28). The density is the whole graph's, before pruning.
        if (hands_off_near_cliques(dens, incumbent)) bb.hand_off_near_cliques();
        // On dense graphs the greedy starts miss the optimum more often and a tighter incumbent
        // prunes the proof, but 4,000 local steps up front (about 2 ms) would cost more than the
        // whole search of a small graph: bbmcx-ls's interleaved local search there instead, a
        // tenth of the search's work (p_hat300-3 509 -> 198 ms, brock400_4 21.6 -> 7.1 s;
        // BENCHMARK.md, section 44).
        std::unique_ptr<LocalSearch> helper;
        if (!near_clique && dens >= kDenseGraph) {
          LocalSearchParams interleaved = ls;
          interleaved.max_steps = LocalSearchParams{}.max_steps;
          interleaved.target = upper;
          helper = std::make_unique<LocalSearch>(sub, interleaved);
          bb.interleave(helper.get(), kLocalInitialVisitsPerVertex * sub.size(), kLocalShare);
        }
        const bool sparse = dens < kDenseGraph && params.decompose_after_words > 0 &&
                            static_cast<long long>(incumbent) * kNearCliqueRatio < sub.size();
        const bool dispersed = sparse && degree_dispersion(g) >= kDispersed;
        const bool wide = near_clique && params.decompose_after_words > 0 &&
                          hands_off_near_cliques(dens, incumbent) && 2LL * incumbent < sub.size();
        // What a node counts for against decompose_after_words: the pruned graph's row words, or
        // a fixed share where the degrees spread wide (the p_hat scheme's, the scans').
        const long long words_per_node = !dispersed                   ? sub.words()
                                         : dens >= kDispersedDensity ? kDispersedWordsPerNode
                                                                     : kSparseDispersedWordsPerNode;
        const long long own_limit =
            budget.nodes + (wide ? kWideNearCliqueNodes
                                 : std::max(1LL, params.decompose_after_words / words_per_node));
        const long long user_limit = budget.node_limit;
        if ((sparse || wide) && (user_limit == 0 || own_limit < user_limit)) {
          budget.node_limit = own_limit;
        }
        bb.run();
        found = bb.best();
        if (helper) ls_steps += helper->steps();
        // Stopped by its own limit (not the caller's, nor the deadline): the decomposition goes on.
        const bool hand_over = budget.node_limit != user_limit && budget.stopped &&
                               SteadyClock::now() < budget.deadline;
        budget.node_limit = user_limit;
        if (hand_over) {
          budget.stopped = false;
          const int size = std::max(incumbent, static_cast<int>(found.size()));
          try {  // a deadline in its set-up keeps BBMCX's clique
            std::vector<int> better =
                wide ? decompose(sub, size, budget, {}, {}, detail::Neighbourhood::kCover)
                     : decompose(sub, size, budget, {},
                                 dens < kDispersedDensity ? kSparseNeighbourhoodSat
                                                          : detail::SatOptions{},
                                 detail::Neighbourhood::kMaxSatCover);
            if (!better.empty()) found = std::move(better);
          } catch (const DeadlinePassed&) {
            budget.stopped = true;
          }
        }
      }
      if (!found.empty()) {
        p.best.clear();
        for (int k : found) p.best.push_back(p.kept[static_cast<std::size_t>(k)]);
      }
    } catch (const DeadlinePassed&) {
      budget.stopped = true;
    }
  CliqueSearchResult r = finish(std::move(p.best), true, budget, upper);
  r.local_search_steps = ls_steps;
  return r;
}

CliqueSearchResult run_greedy(const BitGraph& g, const CliqueSearchParams& p) {
  SearchBudget budget = make_budget(p);
  const CoreDecomposition cd = detail::core_decomposition(g, budget.deadline);
  std::vector<int> clique = detail::greedy_clique(g, cd, budget.deadline, budget.stopped);
  return finish(std::move(clique), false, budget, max_core(cd) + 1);
}

Registry<CliqueAlgorithmInfo>& algorithms() {
  static Registry<CliqueAlgorithmInfo> table("clique algorithm");
  return table;
}

}  // namespace

void CliqueAlgorithms::add(CliqueAlgorithmInfo info) {
  // A limit that passes during set-up (core numbers, orders, relabelling) stops the search before
  // it starts: nothing found yet, status time_limit.
  info.run = [run = std::move(info.run)](const BitGraph& g, const CliqueSearchParams& p) {
    try {
      return run(g, p);
    } catch (const DeadlinePassed&) {
      CliqueSearchResult r;
      r.stopped = true;
      r.upper_bound = g.size();
      return r;
    }
  };
  algorithms().add(std::move(info));
}

const CliqueAlgorithmInfo& CliqueAlgorithms::get(const std::string& name) {
  return algorithms().get(name);
}

std::vector<CliqueAlgorithmInfo> CliqueAlgorithms::list() { return algorithms().list(); }

void register_cliquer();                                                      // cliquer.cpp
void register_igraph();                                                       // igraph.cpp
CliqueSearchResult run_doll(const BitGraph& g, const CliqueSearchParams& p);  // doll.cpp

void register_clique_algorithms() {
  static std::once_flag once;
  std::call_once(once, [] {
    CliqueAlgorithms::add({"bbmc",
                           "BBMC: bitset branch and bound, greedy colouring bound, min-width order",
                           true, run_bbmc<false>});
    CliqueAlgorithms::add({"bbmcr",
                           "BBMCR: BBMC with re-colouring (MCS Re-NUMBER) of branching candidates",
                           true, run_bbmc<true>});
    CliqueAlgorithms::add({"bbmcx",
                           "BBMCX: BBMCR plus the infra-chromatic bound (absorbs a vertex whose "
                           "one neighbour in a class sees none of its neighbours in another)",
                           true, run_bbmc<true, true>});
    CliqueAlgorithms::add({"bbmcx-sat",
                           "BBMCR plus the incremental MaxSAT bound of IncMaxCLQ/MoMC (unit "
                           "propagation and failed literals over the colour classes)",
                           true, run_bbmcx_sat});
    CliqueAlgorithms::add({"bbmcx-ls",
                           "BBMCX with a DLS-MC local search interleaved for the lower bound", true,
                           run_bbmcx_ls});
    CliqueAlgorithms::add(
        {"bbmc-kcore",
         "BBMC after a greedy lower bound and k-core pruning (TEASER++/PMC-style pre-pruning)",
         true, run_bbmc_kcore});
    CliqueAlgorithms::add(
        {"bbmc-dec",
         "BBMC on each vertex's later neighbours in degeneracy order, peeled to their k-core "
         "(PMC-style decomposition)",
         true, run_bbmc_dec});
    CliqueAlgorithms::add(
        {"cover",
         "a few greedy starts, k-core pruning, then the pruned graph's complement: minimum vertex "
         "cover by branch and reduce (LP reductions, cycle-cover bound; Akiba & Iwata 2016)",
         true, run_pruned<false>});
    CliqueAlgorithms::add({"auto",
                           "greedy starts and k-core pruning, then cover when the pruned graph is "
                           "a near-clique (complement density <= 0.25), else BBMCX on it "
                           "(bbmcx-sat with a local search interleaved from density 0.85, "
                           "handed to the neighbourhoods below after 5,000 nodes where the "
                           "clique is a third of the graph; "
                           "from 0.5, or 0.45 where the degrees "
                           "spread twice a random graph's, bbmc-dec's neighbourhoods "
                           "with the MaxSAT bound and bbmcx-ls's local search between them, on "
                           "regular graphs BBMCX with that local search interleaved; the "
                           "neighbourhoods too after a long sparse search, soon where the "
                           "degrees spread twice a random graph's, each recoloured first "
                           "(iterated greedy), the near-clique ones by cover's LP bound, the "
                           "others' long MaxSAT searches by their own neighbourhoods)",
                           true, run_pruned<true>});
    CliqueAlgorithms::add({"doll",
                           "Russian doll search (Ostergard 2002, cliquer's algorithm) on bitsets",
                           true, run_doll});
    CliqueAlgorithms::add({"greedy",
                           "greedy clique by core number: a heuristic, no optimality proof", false,
                           run_greedy});
#ifdef VERIFYBENCH_HAVE_CLIQUER
    register_cliquer();
#endif
#ifdef VERIFYBENCH_HAVE_IGRAPH
    register_igraph();
#endif
  });
}

CliqueSearchResult max_clique(const BitGraph& g, const CliqueSearchParams& params) {
  register_clique_algorithms();
  return CliqueAlgorithms::get(kDefaultCliqueAlgorithm).run(g, params);
}

}  // namespace verifybench
