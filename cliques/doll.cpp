// doll: Östergård's Russian doll search (Östergård 2002, "A fast algorithm for the maximum clique
// problem", the algorithm inside cliquer) on our bitset rows.
//
// Vertices are put in an order v_0 .. v_{n-1} and the dolls are the prefixes S_i = {v_0 .. v_i}.
// c(i) = omega(S_i) is either c(i-1) or c(i-1) + 1, and it is c(i-1) + 1 exactly when v_i has
// c(i-1) pairwise adjacent neighbours below it: each doll is a decision problem, and inside it a
// candidate v_j (taken highest first) cannot complete a clique that needs k more vertices from
// S_j when c(j) < k. Weak on random-like graphs, where a colouring bound prunes far more (brock,
// C125.9: seconds); strong on small vertex-transitive graphs, where the colouring bound is far
// above omega and every c(j) is tight early (hamming8-4, johnson16-2-4).
#include <algorithm>
#include <vector>

#include "cliques/detail/bbmc.hpp"
#include "cliques/max_clique.hpp"

namespace verifybench {

using detail::kBits;
using detail::SearchBudget;
using detail::Word;

namespace {

/// The order cliquer uses for unweighted graphs: colour classes one at a time, each class taking
/// the uncoloured vertex of largest degree among the uncoloured vertices that fits, until none
/// fits (ties to the larger id). The first class becomes the innermost doll. `classes` receives
/// the number of classes: a proper colouring, so an upper bound on omega.
std::vector<int> colour_class_order(const BitGraph& g, int& classes,
                                    SteadyClock::time_point deadline) {
  const int n = g.size(), W = g.words();
  std::vector<int> degree(static_cast<std::size_t>(n)), order;
  order.reserve(static_cast<std::size_t>(n));
  for (int v = 0; v < n; ++v) {
    if ((v & 1023) == 1023) throw_if_past(deadline);
    degree[static_cast<std::size_t>(v)] = g.degree(v);
  }
  std::vector<Word> uncoloured = detail::first_n_set(n, W), fits(uncoloured.size());
  for (classes = 0; static_cast<int>(order.size()) < n; ++classes) {
    fits = uncoloured;
    for (;;) {
      int pick = -1;
      detail::for_each_bit(fits.data(), W, [&](int u) {
        if (pick < 0 ||
            degree[static_cast<std::size_t>(u)] >= degree[static_cast<std::size_t>(pick)])
          pick = u;
      });
      if (pick < 0) break;
      if ((order.size() & 255) == 255) throw_if_past(deadline);
      order.push_back(pick);
      const Word* row = g.row(pick);
      fits[static_cast<std::size_t>(pick / kBits)] &= ~(Word{1} << (pick % kBits));
      uncoloured[static_cast<std::size_t>(pick / kBits)] &= ~(Word{1} << (pick % kBits));
      for (int w = 0; w < W; ++w) {
        for (Word x = row[w] & uncoloured[static_cast<std::size_t>(w)]; x; x &= x - 1)
          --degree[static_cast<std::size_t>(w * kBits + detail::lowest_bit(x))];
        fits[static_cast<std::size_t>(w)] &= ~row[w];
      }
    }
  }
  return order;
}

inline int highest_bit(const Word* bits, int top_word) {
  for (int w = top_word; w >= 0; --w) {
    if (bits[w]) return w * kBits + 63 - __builtin_clzll(bits[w]);
  }
  return -1;
}

class RussianDoll {
 public:
  RussianDoll(const BitGraph& h, SearchBudget& budget)
      : h_(h),
        W_(h.words()),
        budget_(budget),
        c_(static_cast<std::size_t>(h.size()), 0),
        levels_(static_cast<std::size_t>(h.size()) + 1) {}

  /// Solves the dolls S_0, S_1, ... in turn; stops early at `upper` (a bound on omega) or when
  /// the budget runs out. best() is the largest clique met (ids of h).
  void run(int upper) {
    const int n = h_.size();
    int size = 0;
    for (int i = 0; i < n && size < upper; ++i) {
      // Is there a clique of size + 1 through v_i inside S_i? It needs `size` of its neighbours.
      auto& P = level(0);
      const Word* row = h_.row(i);
      const int top = i / kBits;
      for (int w = 0; w < top; ++w) P[static_cast<std::size_t>(w)] = row[w];
      P[static_cast<std::size_t>(top)] = row[top] & ((Word{1} << (i % kBits)) - 1);
      stack_.clear();
      if (size == 0 || find(0, top, size, BitGraph::count(P.data(), top + 1))) {
        stack_.push_back(i);
        best_ = stack_;
        ++size;
      }
      if (budget_.stopped) return;
      c_[static_cast<std::size_t>(i)] = size;
    }
  }
  const std::vector<int>& best() const { return best_; }

 private:
  std::vector<Word>& level(int depth) {
    auto& l = levels_[static_cast<std::size_t>(depth)];
    if (l.empty()) l.assign(static_cast<std::size_t>(W_), 0);
    return l;
  }

  /// Looks for `need` >= 1 pairwise adjacent vertices in the candidate set at `depth` (no bit
  /// above word `top`, `remaining` bits); on success pushes them onto stack_. Candidates go highest
  /// first, and v_j ends the loop once c(j) < need (every candidate left lies in S_j) or fewer than
  /// `need` candidates remain.
  bool find(int depth, int top, int need, int remaining) {
    std::vector<Word>& P = level(depth);
    std::vector<Word>& Q = level(depth + 1);
    for (int v = highest_bit(P.data(), top); v >= 0 && remaining >= need;
         v = highest_bit(P.data(), top)) {
      if (c_[static_cast<std::size_t>(v)] < need) return false;
      if (need == 1) {
        stack_.push_back(v);
        return true;
      }
      if (!budget_.spend()) return false;
      top = v / kBits;
      P[static_cast<std::size_t>(top)] &= ~(Word{1} << (v % kBits));
      --remaining;
      const Word* row = h_.row(v);
      for (int w = 0; w <= top; ++w)
        Q[static_cast<std::size_t>(w)] = P[static_cast<std::size_t>(w)] & row[w];
      const int qcount = BitGraph::count(Q.data(), top + 1);
      if (qcount < need - 1) continue;
      const int q_high = highest_bit(Q.data(), top);
      if (c_[static_cast<std::size_t>(q_high)] < need - 1) continue;
      if (find(depth + 1, q_high / kBits, need - 1, qcount)) {
        stack_.push_back(v);
        return true;
      }
      if (budget_.stopped) return false;
    }
    return false;
  }

  const BitGraph& h_;
  const int W_;
  SearchBudget& budget_;
  std::vector<int> c_;  // c(i) = omega(S_i), for the dolls solved so far
  std::vector<std::vector<Word>> levels_;
  std::vector<int> stack_, best_;
};

}  // namespace

CliqueSearchResult run_doll(const BitGraph& g, const CliqueSearchParams& p) {
  SearchBudget budget = detail::make_budget(p);
  int upper = 0;
  const std::vector<int> order = colour_class_order(g, upper, budget.deadline);
  const BitGraph h = detail::permuted(g, order, budget.deadline);
  RussianDoll doll(h, budget);
  doll.run(upper);
  std::vector<int> clique;
  for (int k : doll.best()) clique.push_back(order[static_cast<std::size_t>(k)]);
  return detail::finish(std::move(clique), true, budget, upper);
}

}  // namespace verifybench
