#pragma once
// BBMC (San Segundo, Rodriguez-Losada & Jimenez 2011): bitset branch and bound for maximum clique
// with a bit-parallel greedy colouring bound. Internal to cliques/; the graph's vertex order is the
// initial order (index 0 is coloured first, so put high-degree / high-core vertices there).
#include <algorithm>
#include <limits>
#include <vector>

#include "cliques/detail/local_search.hpp"
#include "core/deadline.hpp"
#include "core/timer.hpp"
#include "graph/bitgraph.hpp"

namespace verifybench::detail {

using Word = BitGraph::Word;
inline constexpr int kBits = BitGraph::kWordBits;

inline int lowest_bit(Word w) { return __builtin_ctzll(w); }

/// The bitset {0, ..., n - 1} in `words` words (words >= ceil(n / 64)).
inline std::vector<Word> first_n_set(int n, int words) {
  std::vector<Word> bits(static_cast<std::size_t>(words), 0);
  for (int w = 0; w < n / kBits; ++w) bits[static_cast<std::size_t>(w)] = ~Word{0};
  if (n % kBits != 0) bits[static_cast<std::size_t>(n / kBits)] = (Word{1} << (n % kBits)) - 1;
  return bits;
}

/// Calls f(v) for every set bit of a bitset of `words` words, in increasing order.
template <class F>
void for_each_bit(const Word* bits, int words, F&& f) {
  for (int w = 0; w < words; ++w) {
    for (Word x = bits[w]; x; x &= x - 1) f(w * kBits + lowest_bit(x));
  }
}

/// BBMC's bit-parallel greedy colouring of P (rows of `words` words from `rows`): stores the
/// vertices of colour >= kmin in ord/col (room for |P|), returns how many; sets the classes used
/// and |P|. U and Q are scratch bitsets of `words` words. When `low` is not null (kmin - 1 zeroed
/// bitsets of `words` words), class k < kmin is also written to low[k - 1], and, when `low_class`
/// is not null either, low_class[v] = k - 1 for each such vertex v. Compiled for AVX-512, AVX2
/// and baseline x86-64.
int colour_kernel(const Word* P, int words, const Word* rows, int kmin, Word* U, Word* Q, int* ord,
                  int* col, int* classes_used, int* coloured, Word* low = nullptr,
                  int* low_class = nullptr);

/// Whether BBMC's greedy colouring of g (independent sets taken in vertex order) needs at most
/// `k` colours: then no clique has more than k vertices.
bool colours_within(const BitGraph& g, int k);

/// How long recolours_within() goes on.
struct Recolouring {
  int max_rounds = 400;
  int patience = 20;       ///< rounds in a row without fewer colours before it gives up
  int slack_divisor = 16;  ///< gives up at once where the first round exceeds k by over k / this
};

/// Whether some greedy colouring of g needs at most `k` colours (then no clique has more than k
/// vertices), by Culberson and Luo's iterated greedy ("Exploring the k-colorable landscape with
/// iterated greedy", DIMACS 1996): BBMC's colouring, then again with the vertices grouped by the
/// last colouring's classes, which never needs more colours (first-fit keeps each independent
/// class within one); the classes in reverse order and largest first, alternately. On the
/// near-cliques of balm_realworld's scans it closes most gaps of 1-30 colours above the clique a
/// neighbourhood needs (BENCHMARK.md, section 64). `counts`, when given, receives each round's
/// number of colours.
bool recolours_within(const BitGraph& g, int k, const Recolouring& r = {},
                      std::vector<int>* counts = nullptr);

/// Limits shared by every search of one solve: a deadline and a node budget, checked every 64
/// nodes.
struct SearchBudget {
  SteadyClock::time_point deadline;
  long long node_limit = 0;  ///< 0 = none
  long long nodes = 0;
  bool stopped = false;

  bool spend() {  // one node; returns false once out of budget
    if ((++nodes & 63) == 1 || node_limit > 0) {
      if ((node_limit > 0 && nodes >= node_limit) || SteadyClock::now() >= deadline) stopped = true;
    }
    return !stopped;
  }
};

/// Runs `search` with the budget's node limit lowered to `cap` more nodes, where that is below the
/// caller's own limit (cap 0: no cap), then puts the caller's limit back. True when the search
/// stopped on that cap before the deadline: the budget is then running again (stopped cleared)
/// and the caller hands the search over to another.
template <class Search>
bool run_capped(SearchBudget& budget, long long cap, Search&& search) {
  const long long user_limit = budget.node_limit;
  const bool capped = cap > 0 && (user_limit == 0 || budget.nodes + cap < user_limit);
  if (capped) budget.node_limit = budget.nodes + cap;
  search();
  budget.node_limit = user_limit;
  if (!capped || !budget.stopped || SteadyClock::now() >= budget.deadline) return false;
  budget.stopped = false;
  return true;
}

/// A matching of the complement's double cover in a graph's ids (mate_l[u] = v: u_L -- v_R), kept
/// from one lp_rules_out call (cover.hpp) to the next on overlapping vertex sets: its pairs inside
/// the next set start that call's matching (sibling search nodes and the decomposition's
/// consecutive neighbourhoods share most of their vertices). It belongs to one graph: its pairs
/// are that graph's non-edges.
struct LpMatching {
  std::vector<int> mate_l, mate_r;
  std::vector<Word> visited;
};

/// What a search keeps from one near-clique node's hand-off (hand_off_near_clique, cover.hpp) to
/// the next: a zeroed bitset of the graph's words and the LP bound's matching.
struct NearCliqueScratch {
  std::vector<Word> mask;
  LpMatching matching;
};

/// BBMC: branch on vertices in reverse greedy-colour order; prune when |C| + colour <= |best|.
/// The graph may be a whole graph or a compact subproblem; `incumbent` is the size to beat.
/// With `recolour`, a vertex that would get a colour >= kmin is first re-numbered into a lower
/// class when it has a single neighbour there that can move up to another low class (Tomita's
/// Re-NUMBER in MCS; BBMCR of San Segundo et al. 2013): fewer vertices to branch on.
/// With `infra` as well, a vertex that neither fits nor re-numbers is absorbed when it has exactly
/// one neighbour u in a low class C_i and u has no neighbour among v's neighbours in another low
/// class C_j: a clique through v then misses C_i or C_j, so the low classes plus v still hold no
/// clique above kmin - 1 (the infra-chromatic bound of BBMCX, San Segundo, Nikolaev & Batsyn
/// 2015). Each class serves one absorption and is then frozen (re-numbering skips it), so any
/// set of absorbed vertices keeps that bound: a clique through several of them misses one class
/// of each disjoint pair.
class BranchAndBound {
 public:
  BranchAndBound(const BitGraph& g, int incumbent, SearchBudget& budget, bool recolour = false,
                 bool infra = false)
      : g_(g),
        W_(g.words()),
        best_size_(incumbent),
        budget_(budget),
        recolour_(recolour || infra),
        infra_(infra),
        levels_(static_cast<std::size_t>(g.size()) + 2),
        order_(levels_.size()),
        colour_(levels_.size()),
        U_(static_cast<std::size_t>(W_)),
        Q_(static_cast<std::size_t>(W_)) {}

  /// Searches the whole graph; best() is empty unless a clique larger than the incumbent was found.
  void run();
  const std::vector<int>& best() const { return best_; }

  /// Interleaves a local search on the same graph. At the first node and every 1024 nodes it runs
  /// until its work (LocalSearch::work, vertices and words visited) reaches `initial_work` plus
  /// `share` times the words this search has touched colouring, and a larger clique it has found
  /// becomes the incumbent at once (a lower bound is valid anywhere in the tree). Costs a bounded
  /// share of the time; pays where the search meets omega late (brock*: their maximum cliques
  /// hide among low-degree vertices, which greedy colouring orders visit last).
  void interleave(LocalSearch* search, long long initial_work, double share) {
    helper_ = search;
    helper_initial_ = initial_work;
    helper_share_ = share;
  }

  /// Hands every node whose candidates are a near-clique (fewer than about twice the vertices a
  /// better clique needs) to a CoverSearch (cliques/detail/cover.hpp): there the LP bound of the
  /// complement prunes where colourings cannot.
  void hand_off_near_cliques() { cover_ = true; }
  /// A node needing fewer than this many more vertices is not handed off (random dense graphs:
  /// brock200_1 5 s handed off, 0.23 s coloured).
  static constexpr int kMinCover = 32;
  /// The hand-off test on a node's count of candidates: a near-clique has fewer than twice the
  /// vertices a better clique needs, plus a margin (CoverSearch's own test for when its LP bound
  /// of the complement can prune), and needs at least kMinCover.
  static bool near_clique(int candidates, int needed) {
    return needed >= kMinCover && candidates < 2 * needed + kCoverMargin;
  }
  static constexpr int kCoverMargin = 16;

  /// The subgraph induced by `vertices` (ascending ids), vertex k of the result being vertices[k].
  /// `mask` is a zeroed scratch bitset of g.words() words, zeroed again on return.
  static BitGraph induced(const BitGraph& g, const std::vector<int>& vertices,
                          std::vector<Word>& mask);

 private:
  std::vector<Word>& level(int depth) {
    auto& l = levels_[static_cast<std::size_t>(depth)];
    if (l.empty()) l.assign(static_cast<std::size_t>(W_), 0);
    return l;
  }

  // Bit-parallel greedy colouring of P; stores only vertices of colour >= kmin, since the rest can
  // never pass the bound (BBMC's colour-class pruning). Returns how many were stored; sets
  // colours_ (classes used) and coloured_ (|P|).
  int colour(const Word* P, int depth, int kmin);

  // The only neighbour of v (row N) in class C, or -1 when there are none or several.
  int only_neighbour(const Word* C, const Word* N) const;

  // Re-NUMBER: move v into a low class k1 where it has exactly one neighbour u, moving u into a
  // later low class k2 where u has none. Both stay proper colour classes below kmin.
  bool renumber(int v, int low_classes);

  // BBMCX's step for a vertex v that would open a class >= kmin, in one pass over the low
  // classes: for each class C_i where v has exactly one neighbour u, and each other class C_j,
  // the first of: re-number (j > i and u has no neighbour in C_j: u moves to C_j, v takes its
  // place) or absorb (u has no neighbour among v's neighbours in C_j: see the class comment; the
  // pair's classes are then frozen). Taking the first rather than preferring re-numbering costs
  // a few more nodes and less time (the scan of C_j stops early); C_j is scanned from the last
  // (smallest) class, which finds one sooner (BENCHMARK.md, section 5b).
  bool renumber_or_absorb(int v, int low_classes);

  // Long sparse rows (correspondence graphs: 100+ words a row, a few hundred candidates below
  // the root): a node that is about to branch on candidates filling under 1/kSparse of the rows
  // hands its subtree to a search on the subgraph they induce, packed into a few words a row.
  // Vertex order is kept, so every decision is the same; only the word loops shrink (3DMatch
  // corr_6614, 104 words a row: same nodes, less search time; BENCHMARK.md, section 5c).
  // Nodes that prune at once are not worth packing (most children of the root), nor rows of
  // under kCompactWords words (p_hat1000-1, 16 words, is slower packed: its subtrees are small).
  static constexpr int kCompactWords = 32;
  static constexpr long long kMaxInfraWords = 4096;
  // A vertex's pass can also try, for each class where it has one neighbour, every other class:
  // low classes squared times words. Past this the node colours without the pass (a sparse
  // correspondence graph with cliques of 300+ in packed rows of a few words: 72-80% of BBMCX's
  // time there, each failed vertex 10^5-10^6 words; BENCHMARK.md, section 62).
  static constexpr long long kMaxInfraPairWords = 1LL << 18;
  static constexpr int kMaxFailures = 16;
  static constexpr int kSparse = 8;
  bool worth_packing(int candidates) const {
    return W_ >= kCompactWords && candidates * kSparse <= g_.size();
  }
  void search_packed(const Word* P, int size);

  void consult_helper();

  // The hand-off test on P (near_clique() above) and the hand-off.
  bool near_clique(const Word* P, int needed) const;

  void expand(int depth);

  const BitGraph& g_;
  const int W_;
  int best_size_;
  SearchBudget& budget_;
  bool recolour_;
  bool infra_;
  bool cover_ = false;
  BranchAndBound* root_ = this;  // the top search (its local search and incumbent)
  int offset_ = 0;               // vertices of the top search's clique above this graph
  std::vector<Word> mask_;       // search_packed(): zeroed scratch of W_ words
  NearCliqueScratch cover_scratch_;
  LocalSearch* helper_ = nullptr;
  long long helper_initial_ = 0;
  double helper_share_ = 0;
  std::vector<char> frozen_;  // infra: low classes already used by an absorption
  std::vector<int> clique_, best_;
  std::vector<std::vector<Word>> levels_;  // candidate set per depth
  std::vector<std::vector<int>> order_, colour_;
  std::vector<Word> U_, Q_;
  std::vector<Word> classes_;  // the low colour classes, for re-numbering
  int colours_ = 0, coloured_ = 0;
  long long work_ = 0;  // words touched colouring, over all nodes (for interleaving)
};

inline SearchBudget make_budget(const CliqueSearchParams& p) {
  SearchBudget b;
  b.deadline = deadline_after(p.time_limit_s);
  b.node_limit = p.node_limit;
  return b;
}

/// The result of a search: `clique` sorted, optimal when an exact search finished or the clique
/// meets the upper bound.
inline CliqueSearchResult finish(std::vector<int> clique, bool exact, const SearchBudget& budget,
                                 int upper) {
  CliqueSearchResult r;
  std::sort(clique.begin(), clique.end());
  r.clique = std::move(clique);
  r.stopped = budget.stopped;
  r.nodes = budget.nodes;
  r.upper_bound = upper;
  r.optimal = (exact && !budget.stopped) || static_cast<int>(r.clique.size()) == upper;
  if (r.optimal) r.upper_bound = static_cast<int>(r.clique.size());  // proved: the bound is omega
  return r;
}

// The set-up steps of a search (core decomposition, orders, relabelling: O(n^2 / 64) and more, a
// few hundred ms at n = 20,000) call throw_if_past (core/deadline.hpp) once the deadline has
// passed; CliqueAlgorithms turns DeadlinePassed into an empty result with `stopped`, so a limit
// holds before the search starts too.
inline constexpr SteadyClock::time_point kNoDeadline = SteadyClock::time_point::max();

/// The subgraph induced by `vertices` in any order, vertex k of the result being vertices[k].
BitGraph permuted(const BitGraph& g, const std::vector<int>& vertices,
                  SteadyClock::time_point deadline = kNoDeadline);

/// core_decomposition() of max_clique.hpp, throwing DeadlinePassed past `deadline`.
CoreDecomposition core_decomposition(const BitGraph& g, SteadyClock::time_point deadline);
/// greedy_clique() of max_clique.hpp, stopping past `deadline` with the largest clique so far (a
/// partial greedy clique included) and `stopped` set, or after `max_starts` start vertices.
std::vector<int> greedy_clique(const BitGraph& g, const CoreDecomposition& cd,
                               SteadyClock::time_point deadline, bool& stopped,
                               int max_starts = std::numeric_limits<int>::max());

}  // namespace verifybench::detail
