// Core decomposition, the greedy lower bound and the exact clique algorithms of max_clique.hpp.
#include <algorithm>
#include <atomic>
#include <limits>
#include <map>
#include <memory>
#include <mutex>
#include <numeric>
#include <stdexcept>
#include <thread>

#include "cliques/detail/bbmc.hpp"
#include "cliques/detail/cover.hpp"
#include "cliques/detail/sat_bb.hpp"
#include "cliques/max_clique.hpp"
#include "core/detail/multiversion.hpp"
#include "core/parallel.hpp"
#include "core/random.hpp"
#include "core/registry.hpp"

namespace verifybench {

using detail::BranchAndBound;
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
  std::vector<Word> alive(static_cast<std::size_t>(W), 0);
  for (int v = 0; v < n; ++v) alive[static_cast<std::size_t>(v / kBits)] |= Word{1} << (v % kBits);
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

int max_core(const CoreDecomposition& cd) {
  return cd.core.empty() ? -1 : *std::max_element(cd.core.begin(), cd.core.end());
}

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

/// The vertices of `g` left after peeling, again and again, those of degree below k (ascending).
std::vector<int> k_core_of(const BitGraph& g, int k, SteadyClock::time_point deadline) {
  const int n = g.size(), W = g.words();
  std::vector<int> deg(static_cast<std::size_t>(n)), stack;
  std::vector<Word> alive(static_cast<std::size_t>(W), 0);
  for (int v = 0; v < n; ++v) {
    alive[static_cast<std::size_t>(v / kBits)] |= Word{1} << (v % kBits);
    if ((deg[static_cast<std::size_t>(v)] = g.degree(v)) < k) stack.push_back(v);
  }
  for (int v : stack) alive[static_cast<std::size_t>(v / kBits)] &= ~(Word{1} << (v % kBits));
  while (!stack.empty()) {
    const int v = stack.back();
    stack.pop_back();
    const Word* row = g.row(v);
    for (int w = 0; w < W; ++w) {
      for (Word x = row[w] & alive[static_cast<std::size_t>(w)]; x; x &= x - 1) {
        const int u = w * kBits + detail::lowest_bit(x);
        if (--deg[static_cast<std::size_t>(u)] < k) {
          alive[static_cast<std::size_t>(w)] &= ~(Word{1} << (u % kBits));
          stack.push_back(u);
        }
      }
    }
    if ((stack.size() & 255) == 0) throw_if_past(deadline);
  }
  std::vector<int> kept;
  for_each_bit(alive.data(), W, [&](int v) { kept.push_back(v); });
  return kept;
}

// The local search on the pruned graph: a base plus twice the greedy clique (it adds one vertex a
// step, so it needs more steps than the clique it is to reach has vertices).
constexpr long long kLocalBaseSteps = 4000;
constexpr int kNearCliqueRatio = 8;  // the greedy clique is at least 1/8 of the pruned graph
long long local_steps(int greedy) { return kLocalBaseSteps + 2LL * greedy; }
// auto hands near-clique nodes to the cover search on sparse graphs (the correspondence graphs:
// 3DMatch at density 0.07, omega 60, 15% more instructions without it), and on dense ones only
// when the incumbent is this large.
constexpr int kCoverIncumbent = 64;
constexpr double kDenseGraph = 0.5;
// On graphs at least this dense auto searches with the MaxSAT bound (bbmcx-sat, sat_bb.hpp): its
// propagation walks each unit's non-neighbours, so it costs per node what the complement holds.
// On G(n, p) it breaks even with BBMCX at p = 0.9 and costs 0.3-0.95x above it, 1.6-2.5x at
// p = 0.7-0.85 (BENCHMARK.md, section 42). Correspondence graphs are far sparser.
constexpr double kMaxSatDensity = 0.9;
double density(const BitGraph& g) {
  const double n = g.size();
  return n > 1 ? 2.0 * static_cast<double>(g.edge_count()) / (n * (n - 1)) : 0.0;
}
bool hands_off_near_cliques(double graph_density, int incumbent) {
  return incumbent >= kCoverIncumbent || graph_density < kDenseGraph;
}

// On a sparse graph that is no near-clique, auto's BBMCX colours the whole pruned graph at each
// node, and its classes mix far-apart regions. Past params.decompose_after_words of rows coloured
// (nodes times the pruned graph's words) it hands the search to the decomposition of bbmc-dec with
// the MaxSAT bound in each neighbourhood (LMC's scheme), from its incumbent. On the corpus every
// sparse search BBMCX proves stays under 2.8e7 (k00_198_94 0.3 k10: 71,401 nodes of 391 words,
// 2.4 s), and the two it does not prove in 30 s (k00_198_94 0.5 k3/k10, omega 120 and 110) are
// proved in 6.4 and 8.7 s this way; the DIMACS graphs never get there (BENCHMARK.md, section 43).

/// The largest clique above `incumbent` (ids of g) by the decomposition with the MaxSAT bound in
/// each neighbourhood, or empty; budget.stopped when the budget ran out first.
std::vector<int> decompose(const BitGraph& g, int incumbent, SearchBudget& budget);

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
      const bool near_clique = static_cast<long long>(incumbent) * kNearCliqueRatio >= sub.size();
      std::vector<int> local;
      if (near_clique) {
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
      std::vector<int> found;
      if (sub.size() <= incumbent) {
        upper = std::min(upper, incumbent);
      } else if (!kAuto) {
        detail::CoverSearch cover(sub, incumbent, budget);
        cover.run();
        found = cover.best();
        upper = std::min(upper, cover.upper_bound());
      } else if (dens >= kMaxSatDensity) {
        detail::SatBranchAndBound bb(sub, incumbent, budget);
        if (hands_off_near_cliques(dens, incumbent)) {
          bb.hand_off_near_cliques(BranchAndBound::kMinCover);
        }
        bb.run();
        found = bb.best();
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
        const long long own_limit = budget.nodes + params.decompose_after_words / sub.words();
        const long long user_limit = budget.node_limit;
        if (sparse && (user_limit == 0 || own_limit < user_limit)) budget.node_limit = own_limit;
        bb.run();
        found = bb.best();
        if (helper) ls_steps += helper->steps();
        if (budget.node_limit != user_limit && budget.stopped &&
            SteadyClock::now() < budget.deadline) {
          budget.stopped = false;
          budget.node_limit = user_limit;
          const int size = std::max(incumbent, static_cast<int>(found.size()));
          try {  // a deadline in its set-up keeps BBMCX's clique
            std::vector<int> better = decompose(sub, size, budget);
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

// |row & mask| over the listed words, with the hardware popcount where the CPU has one.
VB_MULTIVERSION_POPCNT
int count_in(const Word* row, const Word* mask, const int* words, int count) {
  int d = 0;
  for (int i = 0; i < count; ++i) d += __builtin_popcountll(row[words[i]] & mask[words[i]]);
  return d;
}

// bbmc-dec: every maximum clique has a first vertex v in degeneracy order, and its other vertices
// are later neighbours of v: at most degeneracy of them. Solving each such neighbourhood as a small
// compact BBMC problem, highest core first, is what PMC does (with a weaker bound inside).
class Decomposition {
 public:
  Decomposition(const BitGraph& g, SteadyClock::time_point deadline)
      : cd_(detail::core_decomposition(g, deadline)),
        order_(cd_.order.rbegin(), cd_.order.rend()),
        // Relabel in min-width order (0 = removed last): v's later neighbours are the smaller ids.
        h_(detail::permuted(g, order_, deadline)) {}

  const CoreDecomposition& cores() const { return cd_; }
  int size() const { return h_.size(); }

  /// Per-worker scratch of solve(): a zeroed bitset of h_'s width and two buffers.
  struct Scratch {
    explicit Scratch(const BitGraph& g) : mask(static_cast<std::size_t>(g.words()), 0) {}
    std::vector<Word> mask;
    std::vector<int> members, words;
  };

  /// A clique through v larger than `size` whose other vertices are v's later neighbours, in
  /// original ids (the maximum such clique, the first the search meets), or empty when there is
  /// none. The search is BBMC, or with `max_sat` the MaxSAT bound of sat_bb.hpp (as LMC does).
  std::vector<int> solve(int v, int size, SearchBudget& budget, Scratch& s,
                         bool max_sat = false) const {
    if (core(v) + 1 <= size) return {};  // v's later degree is at most its core number
    std::vector<int>& members = s.members;
    members.clear();
    const Word* row = h_.row(v);
    for (int w = 0; w <= v / kBits; ++w) {
      for (Word x = row[w]; x; x &= x - 1) {
        const int u = w * kBits + detail::lowest_bit(x);
        if (u >= v) break;
        if (core(u) >= size) members.push_back(u);
      }
    }
    if (static_cast<int>(members.size()) + 1 <= size) return {};
    peel(size - 1, s);
    if (static_cast<int>(members.size()) + 1 <= size) return {};
    BitGraph sub = BranchAndBound::induced(h_, members, s.mask);
    // The subgraph is at most the degeneracy: its peel needs no deadline (nor a throw in a worker).
    std::vector<int> core = k_core_of(sub, size - 1, detail::kNoDeadline);
    if (static_cast<int>(core.size()) + 1 <= size) return {};
    if (core.size() < members.size()) {
      std::size_t kept = 0;
      for (int k : core) members[kept++] = members[static_cast<std::size_t>(k)];
      members.resize(kept);
      sub = BranchAndBound::induced(h_, members, s.mask);
    }
    std::vector<int> found;
    if (max_sat) {
      detail::SatBranchAndBound bb(sub, size - 1, budget);
      bb.run();
      found = bb.best();
    } else {
      BranchAndBound bb(sub, size - 1, budget);
      bb.run();
      found = bb.best();
    }
    if (found.empty()) return {};
    std::vector<int> clique{order_[static_cast<std::size_t>(v)]};
    for (int k : found)
      clique.push_back(order_[static_cast<std::size_t>(members[static_cast<std::size_t>(k)])]);
    return clique;
  }

 private:
  // Drops the members with fewer than k neighbours among the members (a clique of k + 1 members
  // has k in each; LMC's reduction, Jiang, Li & Manya, ECAI 2016), in one pass over h_'s rows and
  // a bitset of the members, before the subgraph is built; solve() then peels the subgraph to its
  // k-core. On the sparse negatives of the corpus (n 23,000-25,000, omega 110-120) about one
  // subproblem in ten survives (2,400 of 23,000 at a clique of 110): 13.8 -> 11.1 s for bbmc-dec.
  void peel(int k, Scratch& s) const {
    s.words.clear();
    for (int u : s.members) {
      const int w = u / kBits;
      if (s.mask[static_cast<std::size_t>(w)] == 0) s.words.push_back(w);
      s.mask[static_cast<std::size_t>(w)] |= Word{1} << (u % kBits);
    }
    for (int u : s.members) {
      const int d = count_in(h_.row(u), s.mask.data(), s.words.data(),
                             static_cast<int>(s.words.size()));
      if (d < k) s.mask[static_cast<std::size_t>(u / kBits)] &= ~(Word{1} << (u % kBits));
    }
    std::size_t kept = 0;
    for (int u : s.members) {
      if ((s.mask[static_cast<std::size_t>(u / kBits)] >> (u % kBits)) & 1) s.members[kept++] = u;
    }
    s.members.resize(kept);
    for (int w : s.words) s.mask[static_cast<std::size_t>(w)] = 0;
  }

  int core(int relabelled) const {
    return cd_.core[static_cast<std::size_t>(order_[static_cast<std::size_t>(relabelled)])];
  }
  CoreDecomposition cd_;
  std::vector<int> order_;
  BitGraph h_;
};

std::vector<int> decompose(const BitGraph& g, int incumbent, SearchBudget& budget) {
  const Decomposition dec(g, budget.deadline);
  Decomposition::Scratch scratch(g);
  std::vector<int> best;
  for (int v = 0; v < dec.size() && !budget.stopped; ++v) {
    const int size = std::max(incumbent, static_cast<int>(best.size()));
    std::vector<int> found = dec.solve(v, size, budget, scratch, true);
    if (!found.empty()) best = std::move(found);
  }
  return best;
}

// Parallel over vertices with a shared incumbent size, then a canonical answer so that the clique
// does not depend on the thread count: the first vertex (in min-width order) through which a
// maximum clique runs, and the first maximum clique BBMC meets there with incumbent omega - 1.
// Phase 1 records, per vertex, the size it proved no larger clique through it exceeds, so the
// canonical pass re-solves only vertices that phase 1 could not rule out (with one thread: one).
CliqueSearchResult run_bbmc_dec(const BitGraph& g, const CliqueSearchParams& p) {
  const SteadyClock::time_point deadline = deadline_after(p.time_limit_s);
  const Decomposition dec(g, deadline);
  const int n = dec.size();
  const int upper = max_core(dec.cores()) + 1;
  SearchBudget greedy_budget;
  std::vector<int> best = detail::greedy_clique(g, dec.cores(), deadline, greedy_budget.stopped);
  if (greedy_budget.stopped) return finish(std::move(best), true, greedy_budget, upper);
  const int threads = resolve_threads(p.threads);

  std::atomic<int> next{0}, best_size{static_cast<int>(best.size())};
  std::atomic<bool> stop{false};
  std::mutex lock;
  int first = n;  // smallest vertex through which phase 1 met a clique of the current best size
  std::vector<int> proven(static_cast<std::size_t>(n), std::numeric_limits<int>::max());
  // Every budget keeps the deadline taken before the set-up: make_budget(p) here would restart the
  // clock after the greedy starts (on a 4,500-vertex near-clique they took 14 s of a 20 s limit,
  // and the search then ran 20 s more).
  SearchBudget phase = make_budget(p);
  phase.deadline = deadline;
  std::vector<SearchBudget> budgets(static_cast<std::size_t>(threads), phase);
  auto worker = [&](SearchBudget& budget) {
    Decomposition::Scratch scratch(g);
    for (int v; !stop && (v = next++) < n && best_size.load() < upper;) {
      const int size = best_size.load();
      std::vector<int> found = dec.solve(v, size, budget, scratch);
      if (budget.stopped) {
        stop = true;
        return;
      }
      proven[static_cast<std::size_t>(v)] = found.empty() ? size : static_cast<int>(found.size());
      if (found.empty()) continue;
      std::lock_guard<std::mutex> guard(lock);
      if (found.size() > best.size() || (found.size() == best.size() && v < first)) {
        first = v;
        best = std::move(found);
        best_size = static_cast<int>(best.size());
      }
    }
  };
  WorkerPool(threads).parallel_for(threads,
                                   [&](int t) { worker(budgets[static_cast<std::size_t>(t)]); });
  SearchBudget total = budgets[0];
  for (std::size_t t = 1; t < budgets.size(); ++t) total.nodes += budgets[t].nodes;
  total.stopped = stop;
  if (!stop && first < n) {
    const int omega = static_cast<int>(best.size());
    Decomposition::Scratch scratch(g);
    SearchBudget canonical = phase;
    for (int v = 0; v <= first; ++v) {
      if (proven[static_cast<std::size_t>(v)] < omega) continue;  // no omega-clique through v
      std::vector<int> found = dec.solve(v, omega - 1, canonical, scratch);
      if (!found.empty()) {
        best = std::move(found);
        break;
      }
    }
    total.nodes += canonical.nodes;
    total.stopped = canonical.stopped;
  }
  return finish(std::move(best), true, total, upper);
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
                           "a near-clique (complement density <= 0.25), else BBMCX on it (bbmcx-sat "
                           "from density 0.9, with bbmcx-ls's local search interleaved from 0.5; "
                           "a long sparse search goes on in bbmc-dec's neighbourhoods with the "
                           "MaxSAT bound)",
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
