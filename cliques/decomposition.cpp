// The degeneracy decomposition (PMC's scheme, LMC's reductions): bbmc-dec, and the search auto
// hands long sparse searches to (cliques/bbmc_variants.cpp).
#include "cliques/detail/decomposition.hpp"

#include <atomic>
#include <mutex>
#include <optional>

#include "cliques/detail/cover.hpp"
#include "cliques/detail/kernel.hpp"
#include "cliques/detail/sat_bb.hpp"
#include "core/detail/multiversion.hpp"
#include "core/parallel.hpp"

namespace verifybench::detail {

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
        const int u = w * kBits + lowest_bit(x);
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

BitGraph core_subgraph(const BitGraph& g, std::vector<int>& members, int target,
                       std::vector<Word>& mask, SteadyClock::time_point deadline) {
  BitGraph sub = BranchAndBound::induced(g, members, mask);
  const std::vector<int> core = k_core_of(sub, target, deadline);
  if (core.size() == members.size()) return sub;
  std::size_t kept = 0;
  for (int k : core) members[kept++] = members[static_cast<std::size_t>(k)];
  members.resize(kept);
  return BranchAndBound::induced(g, members, mask);
}

namespace {

// kMaxSatCover's neighbourhoods that are no near-cliques but have fewer members than 9/4 of the
// clique they need hand their MaxSAT search to the cover search (after kSatNodesBeforeHandOver).
constexpr long long kCoverBandQuarters = 9;

// Whether |row & mask| over the listed words reaches k, with the hardware popcount where the CPU
// has one; it stops counting there.
VB_MULTIVERSION_POPCNT
bool counts_at_least(const Word* row, const Word* mask, const int* words, int count, int k) {
  if (k <= 0) return true;
  int d = 0;
  for (int i = 0; i < count; ++i) {
    d += __builtin_popcountll(row[words[i]] & mask[words[i]]);
    if (d >= k) return true;
  }
  return false;
}

// bbmc-dec: every maximum clique has a first vertex v in degeneracy order, and its other vertices
// are later neighbours of v: at most degeneracy of them. Solving each such neighbourhood as a small
// compact BBMC problem, highest core first, is what PMC does (with a weaker bound inside).
class Decomposition {
 public:
  Decomposition(const BitGraph& g, SteadyClock::time_point deadline)
      : cd_(core_decomposition(g, deadline)),
        order_(cd_.order.rbegin(), cd_.order.rend()),
        // Relabel in min-width order (0 = removed last): v's later neighbours are the smaller ids.
        h_(permuted(g, order_, deadline)) {}

  const CoreDecomposition& cores() const { return cd_; }

  /// Colours the relabelled graph first-fit in id order, as BBMC colours its root (a class takes
  /// each vertex, in order, that sees none of it): a clique of vertices 0..v, whose other
  /// vertices are v's later neighbours, has at most as many vertices as 0..v use colours.
  void colour_prefixes() {
    const int n = h_.size(), W = h_.words();
    std::vector<Word> left = first_n_set(n, W), q(static_cast<std::size_t>(W));
    std::vector<int> colour(static_cast<std::size_t>(n), 0);
    for (int c = 1, first = 0; first < W; ++c) {
      q = left;
      for (int w = first; w < W; ++w) {
        while (q[static_cast<std::size_t>(w)]) {
          const int v = w * kBits + lowest_bit(q[static_cast<std::size_t>(w)]);
          colour[static_cast<std::size_t>(v)] = c;
          left[static_cast<std::size_t>(w)] &= ~(Word{1} << (v % kBits));
          const Word* row = h_.row(v);
          for (int x = w; x < W; ++x) q[static_cast<std::size_t>(x)] &= ~row[x];
          q[static_cast<std::size_t>(w)] &= ~(Word{1} << (v % kBits));
        }
      }
      while (first < W && left[static_cast<std::size_t>(first)] == 0) ++first;
    }
    prefix_colours_.assign(static_cast<std::size_t>(n), 0);
    int used = 0;
    for (int v = 0; v < n; ++v) {
      used = std::max(used, colour[static_cast<std::size_t>(v)]);
      prefix_colours_[static_cast<std::size_t>(v)] = used;
    }
  }
  int size() const { return h_.size(); }
  void set_sat_nodes_before_hand_over(long long nodes) { sat_nodes_before_hand_over_ = nodes; }
  void set_nesting(int levels) { nesting_ = levels; }

  /// Per-worker scratch of solve(): a zeroed bitset of h_'s width and two buffers.
  struct Scratch {
    explicit Scratch(const BitGraph& g) : mask(static_cast<std::size_t>(g.words()), 0) {}
    std::vector<Word> mask;
    std::vector<int> members, words;
    LpMatching matching;  // kCover's, from one neighbourhood to the next
  };

  /// A clique through v larger than `size` whose other vertices are v's later neighbours, in
  /// original ids (the maximum such clique, the first the search meets), or empty when there is
  /// none. The search is BBMC, the MaxSAT bound of sat_bb.hpp (as LMC does) or the cover search
  /// (decompose()'s Neighbourhood). With kMaxSat, `options` are SatBranchAndBound's and `work`
  /// (when given) adds the words its search touched colouring.
  std::vector<int> solve(int v, int size, SearchBudget& budget, Scratch& s,
                         Neighbourhood search = Neighbourhood::kBbmc, SatOptions options = {},
                         long long* work = nullptr) const {
    if (core(v) + 1 <= size) return {};  // v's later degree is at most its core number
    if (!prefix_colours_.empty() && prefix_colours_[static_cast<std::size_t>(v)] <= size) return {};
    std::vector<int>& members = s.members;
    members.clear();
    const Word* row = h_.row(v);
    for (int w = 0; w <= v / kBits; ++w) {
      for (Word x = row[w]; x; x &= x - 1) {
        const int u = w * kBits + lowest_bit(x);
        if (u >= v) break;
        if (core(u) >= size) members.push_back(u);
      }
    }
    if (static_cast<int>(members.size()) + 1 <= size) return {};
    peel(size - 1, s);
    if (static_cast<int>(members.size()) + 1 <= size) return {};
    // kMaxSatCover: a neighbourhood under twice the clique it needs is a near-clique, where the
    // MaxSAT bound, off by the hundreds its colour classes hold, grows the incumbent one vertex
    // a neighbourhood (balm_realworld's b125_0 FPFH 0.5 k3: 529 -> 580 in 30 s, 446-408,000
    // nodes each) and the complement's LP bound proves it (585 in 2.5 s; BENCHMARK.md, section 63).
    const bool hand_off = search == Neighbourhood::kMaxSatCover;
    const bool near =
        hand_off && BranchAndBound::near_clique(static_cast<int>(members.size()), size);
    // The hand-off's searches for cliques of kMinCover or more: recoloured first, and (past the
    // near-cliques) searched in their own order.
    const bool large = hand_off && size >= BranchAndBound::kMinCover;
    // Just past the near-clique ratio the MaxSAT search is mostly the faster, but a few of its
    // searches run to 100,000s of nodes, which the cover search ends in about a second (b125_0 0.3
    // k3: three neighbourhoods of 1,680 members needing 831, 40 s of 58): past
    // sat_nodes_before_hand_over_ nodes (kSatNodesBeforeHandOver unless decompose() is told
    // otherwise) it hands over.
    const bool sat_then_cover =
        large && !near && kCoverBandQuarters * size > 4LL * static_cast<long long>(members.size());
    if (hand_off) search = near ? Neighbourhood::kCover : Neighbourhood::kMaxSat;
    // kCover: the LP bound on h_'s rows under a mask of the members, from the last neighbourhood's
    // matching, ends most neighbourhoods before their subgraph is built (k00_199_198 0.5 k10:
    // 4,300 of them; BENCHMARK.md, section 52). On the members' k-core (below) it can only be
    // tighter, so this only skips work.
    if (search == Neighbourhood::kCover && lp_rules_out_of_members(v, size - 1, s)) return {};
    const std::size_t peeled = members.size();
    // The subgraph is at most the degeneracy: its peel needs no deadline (nor a throw in a worker).
    const BitGraph sub = core_subgraph(h_, members, size - 1, s.mask, kNoDeadline);
    if (sub.size() + 1 <= size) return {};
    // In kMaxSatCover's hand-off most neighbourhoods that need a clique of hundreds are ruled out
    // by a colouring, as the MaxSAT search's root would do (b112_72 0.5 k1: 1,100 of those the
    // cover search takes; 1.5x the time without it), and of those a first colouring leaves, most
    // by recolouring (recolours_within()): of b176_114 FPFH 0.5 k3's 2,220 neighbourhoods that
    // need 869, a first colouring leaves 432, 20 rounds of recolouring 103; with the kept
    // setting it proves the dump in 17 s, not 38 (section 64). Those ruled out this way spend no
    // node, so the deadline is read here.
    if (large) {
      if (SteadyClock::now() >= budget.deadline) {
        budget.stopped = true;
        return {};
      }
      if (recolours_within(sub, size - 1)) return {};
    }
    // A neighbourhood that is no near-clique, nor in kCoverBandQuarters' band, is reduced to the
    // complement's kernel (cliques/detail/kernel.hpp): on balm_realworld's b112_72 FPFH 0.3 k3,
    // neighbourhoods of 800-850 members at density 0.91 needing 322 keep 670-710 needing 246-261,
    // and searches of 1-20 s end in under 5 ms (BENCHMARK.md, section 67). The kernel is then
    // decomposed again (decomposed_again()). The kernel's merged vertices slow the cover search,
    // so the other paths keep the neighbourhood as it is.
    const BitGraph* graph = &sub;
    int target = size - 1;
    std::optional<CliqueKernel> kernel;
    if (large && !near && !sat_then_cover) {
      kernel.emplace(sub);
      graph = &kernel->graph();
      target -= kernel->credit();
      if (graph->size() <= target) return {};
      if (target < 0) {  // the credit alone beats `size`: the kernel's clique, however small
        if (graph->size() == 0) return lifted(v, members, kernel->lift({}));
        target = 0;
      }
    }
    std::vector<int> found;
    if (search == Neighbourhood::kMaxSat && large && !sat_then_cover && nesting_ > 0) {
      found = sat_then_decomposed(*graph, target, budget, options, work);
    } else if (search == Neighbourhood::kMaxSat && large) {  // in the band, or nested too deep
      found = sat_search_in_own_order(*graph, target, budget, options,
                                      sat_then_cover ? sat_nodes_before_hand_over_ : 0, work);
    } else if (search == Neighbourhood::kMaxSat) {
      found = sat_search(*graph, target, budget, options,
                         sat_then_cover ? sat_nodes_before_hand_over_ : 0, work);
    } else if (search == Neighbourhood::kCover) {
      // A near-clique's neighbourhoods are near-cliques: the LP bound above ruled most of them
      // out; on the k-core, when the peel took vertices, it may rule out more; BBMCX, handing its
      // near-clique nodes to the cover search, takes the rest.
      if (members.size() < peeled && lp_rules_out(sub, size - 1)) return {};
      found = cover_search(sub, size - 1, budget);
    } else {
      BranchAndBound bb(sub, size - 1, budget);
      bb.run();
      found = bb.best();
    }
    if (found.empty()) return {};
    return lifted(v, members, kernel ? kernel->lift(found) : found);
  }

 private:
  // The clique through v whose other vertices are `found` (ids of v's neighbourhood subgraph,
  // vertex k being members[k]), in g's ids.
  std::vector<int> lifted(int v, const std::vector<int>& members,
                          const std::vector<int>& found) const {
    std::vector<int> clique{order_[static_cast<std::size_t>(v)]};
    for (int k : found)
      clique.push_back(order_[static_cast<std::size_t>(members[static_cast<std::size_t>(k)])]);
    return clique;
  }

  static std::vector<int> cover_search(const BitGraph& sub, int target, SearchBudget& budget) {
    BranchAndBound bb(sub, target, budget, true, true);
    bb.hand_off_near_cliques();
    bb.run();
    return bb.best();
  }

  // SatBranchAndBound on sub; stopped after `cover_after` nodes (when not 0; not by the caller's
  // limits) it hands the neighbourhood to the cover search, from what it found.
  static std::vector<int> sat_search(const BitGraph& sub, int target, SearchBudget& budget,
                                     SatOptions options, long long cover_after, long long* work) {
    SatBranchAndBound bb(sub, target, budget, options);
    const bool hand_over = run_capped(budget, cover_after, [&] { bb.run(); });
    if (work) *work += bb.work();
    std::vector<int> found = bb.best();
    if (!hand_over) return found;
    std::vector<int> better =
        cover_search(sub, std::max(target, static_cast<int>(found.size())), budget);
    return better.empty() ? found : better;
  }

  // sat_search on g relabelled in its own min-width order, as bbmcx-sat orders a whole graph: a
  // neighbourhood keeps the order of the whole graph's decomposition, which is not its own. On
  // balm_realworld's b112_72 FPFH 0.3 k3 its MaxSAT searches went from 3 million nodes without
  // the proof in 30 s to 7,900 and the proof in 5.7 s (BENCHMARK.md, section 68).
  static std::vector<int> sat_search_in_own_order(const BitGraph& g, int target,
                                                  SearchBudget& budget, SatOptions options,
                                                  long long cover_after, long long* work) {
    const CoreDecomposition cd = core_decomposition(g, kNoDeadline);
    const std::vector<int> order(cd.order.rbegin(), cd.order.rend());
    std::vector<int> found =
        sat_search(permuted(g, order), target, budget, options, cover_after, work);
    for (int& k : found) k = order[static_cast<std::size_t>(k)];
    return found;
  }

  // A kernel's MaxSAT search, in its own order, and past sat_nodes_before_hand_over_ nodes (not
  // by the caller's limits) the kernel searched as the hand-off searches the whole graph:
  // decomposed in its own degeneracy order, each of its neighbourhoods peeled, recoloured,
  // kernelised and so on down (LMC's first-level scheme). Some kernels are dense (0.85-0.95) with
  // cliques of 35-45% of their vertices: a first colouring leaves 50 of 871 vertices to branch
  // on, and the MaxSAT search branches near its root for millions of nodes (balm_realworld's
  // b112_72 FPFH 0.5 k10: a kernel of 871 vertices needing 336, unproved after 2.6 million
  // nodes; decomposed, 1,148 nodes and 0.27 s). Decomposing every kernel at once costs where the
  // MaxSAT search ends soon (b148_51 0.5 k10 unproved at 30 s, b112_72 0.3 k10 1.8x the time);
  // after 5,000 nodes no dump of the corpus or of balm_realworld changes status, and no search
  // gets slower (BENCHMARK.md, section 70).
  std::vector<int> sat_then_decomposed(const BitGraph& kernel, int target, SearchBudget& budget,
                                       SatOptions options, long long* work) const {
    std::vector<int> found;
    if (!run_capped(budget, sat_nodes_before_hand_over_, [&] {
          found = sat_search_in_own_order(kernel, target, budget, options, 0, work);
        })) {
      return found;
    }
    std::vector<int> better =
        decomposed_again(kernel, std::max(target, static_cast<int>(found.size())), budget, options);
    return better.empty() ? found : better;
  }

  std::vector<int> decomposed_again(const BitGraph& kernel, int target, SearchBudget& budget,
                                    SatOptions options) const {
    try {
      return decompose(kernel, target, budget, {}, options, Neighbourhood::kMaxSatCover,
                       sat_nodes_before_hand_over_, nesting_ - 1);
    } catch (const DeadlinePassed&) {  // in its set-up, before it found anything
      budget.stopped = true;
      return {};
    }
  }

  bool lp_rules_out_of_members(int v, int target, Scratch& s) const {
    for (int u : s.members) s.mask[static_cast<std::size_t>(u / kBits)] |= Word{1} << (u % kBits);
    const bool out = lp_rules_out(h_, s.members, s.mask.data(), v / kBits + 1, target, s.matching);
    for (int u : s.members) s.mask[static_cast<std::size_t>(u / kBits)] = 0;
    return out;
  }

  // Drops the members with fewer than k neighbours among the members (a clique of k + 1 members
  // has k in each; LMC's reduction, Jiang, Li & Manya, ECAI 2016), in one pass over h_'s rows and
  // a bitset of the members, before the subgraph is built; solve() then peels the subgraph to its
  // k-core. On the sparse negatives of the corpus (n 23,000-25,000, omega 110-120) about one
  // subproblem in ten survives (2,400 of 23,000 at a clique of 110): 13.8 -> 11.1 s for bbmc-dec.
  // When too many drop for a clique of k + 1, it empties the members (BENCHMARK.md, section 65).
  void peel(int k, Scratch& s) const {
    s.words.clear();
    for (int u : s.members) {
      const int w = u / kBits;
      if (s.mask[static_cast<std::size_t>(w)] == 0) s.words.push_back(w);
      s.mask[static_cast<std::size_t>(w)] |= Word{1} << (u % kBits);
    }
    // The largest ids first: removed earliest in the degeneracy order, of lower core, they are
    // the likeliest to drop, and each one dropped leaves the others fewer. Once more have
    // dropped than the members have to spare, no clique of k + 1 is left among them.
    const int spare = static_cast<int>(s.members.size()) - (k + 1);
    int dropped = 0;
    for (auto it = s.members.rbegin(); it != s.members.rend() && dropped <= spare; ++it) {
      const int u = *it;
      if (!counts_at_least(h_.row(u), s.mask.data(), s.words.data(),
                           static_cast<int>(s.words.size()), k)) {
        s.mask[static_cast<std::size_t>(u / kBits)] &= ~(Word{1} << (u % kBits));
        ++dropped;
      }
    }
    std::size_t kept = 0;
    if (dropped <= spare) {
      for (int u : s.members) {
        if ((s.mask[static_cast<std::size_t>(u / kBits)] >> (u % kBits)) & 1) {
          s.members[kept++] = u;
        }
      }
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
  std::vector<int> prefix_colours_;  // colours of vertices 0..v (colour_prefixes()), or empty
  long long sat_nodes_before_hand_over_ = kSatNodesBeforeHandOver;
  int nesting_ = kMaxNesting;
};

}  // namespace

std::vector<int> decompose(const BitGraph& g, int incumbent, SearchBudget& budget,
                           const Interleaved& helper, SatOptions options, Neighbourhood search,
                           long long sat_nodes_before_hand_over, int nesting) {
  Decomposition dec(g, budget.deadline);
  dec.set_sat_nodes_before_hand_over(sat_nodes_before_hand_over);
  dec.set_nesting(nesting);
  // On near-cliques the colouring rules out the first vertices at once (k00_199_198 0.3 k3
  // through the decomposition alone: 24.5 -> 18.1 s; BENCHMARK.md, section 51).
  if (search == Neighbourhood::kCover) dec.colour_prefixes();
  Decomposition::Scratch scratch(g);
  std::vector<int> best;
  long long work = 0;
  for (int v = 0; v < dec.size() && !budget.stopped; ++v) {
    LocalSearch* ls = helper.search;
    if (ls && ls->keep_pace(helper.initial_work, helper.share, work,
                            std::max(static_cast<int>(best.size()), incumbent), budget.deadline)) {
      best = ls->best();
    }
    const int size = std::max(incumbent, static_cast<int>(best.size()));
    std::vector<int> found = dec.solve(v, size, budget, scratch, search, options, &work);
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
  std::vector<int> best = greedy_clique(g, dec.cores(), deadline, greedy_budget.stopped);
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

}  // namespace verifybench::detail
