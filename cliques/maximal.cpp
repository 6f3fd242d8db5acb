// Maximal clique enumeration: Bron-Kerbosch with Tomita pivoting, run per vertex in degeneracy
// order on the compact subgraph of its neighbours (Eppstein, Loffler & Strash 2010), so each
// maximal clique is reported once, from its first vertex in that order.
#include <functional>

#include "cliques/detail/bbmc.hpp"
#include "cliques/max_clique.hpp"

namespace verifybench {

namespace {

using detail::kBits;
using detail::lowest_bit;
using detail::Word;

/// Bron-Kerbosch with pivoting on a compact graph; reports every maximal clique R + (clique of P)
/// whose vertices are not all extendable by X.
class MaximalCliques {
 public:
  MaximalCliques(const BitGraph& g, int min_size, detail::SearchBudget& budget,
                 std::function<bool(const std::vector<int>&)> report)
      : g_(g), W_(g.words()), min_size_(min_size), budget_(budget), report_(std::move(report)) {}

  /// Cliques that contain `root` (not in g) plus vertices of P, excluding those that X extends.
  void run(std::vector<Word> P, std::vector<Word> X) {
    levels_.clear();
    levels_.push_back({std::move(P), std::move(X)});
    expand(0, 1);
  }

 private:
  struct Level {
    std::vector<Word> P, X;
  };

  void expand(int depth, int size) {
    if (!budget_.spend()) return;
    const Level& L = levels_[static_cast<std::size_t>(depth)];
    int p_count = 0;
    for (int w = 0; w < W_; ++w) p_count += __builtin_popcountll(L.P[static_cast<std::size_t>(w)]);
    if (p_count == 0) {
      bool x_empty = true;
      for (int w = 0; w < W_ && x_empty; ++w) x_empty = L.X[static_cast<std::size_t>(w)] == 0;
      if (x_empty && size >= min_size_ && !report_(R_)) budget_.stopped = true;
      return;
    }
    if (size + p_count < min_size_) return;  // cannot reach the smallest reported size
    // Tomita pivot: the vertex of P or X with most neighbours in P.
    int pivot = -1, best = -1;
    for (const auto* S : {&L.P, &L.X}) {
      detail::for_each_bit(S->data(), W_, [&](int u) {
        int c = 0;
        const Word* N = g_.row(u);
        for (int w = 0; w < W_; ++w)
          c += __builtin_popcountll(L.P[static_cast<std::size_t>(w)] & N[w]);
        if (c > best) best = c, pivot = u;
      });
    }
    std::vector<Word> P = L.P, X = L.X;
    std::vector<int> branch;
    const Word* Npivot = g_.row(pivot);
    for (int w = 0; w < W_; ++w) {
      for (Word x = P[static_cast<std::size_t>(w)] & ~Npivot[w]; x; x &= x - 1)
        branch.push_back(w * kBits + lowest_bit(x));
    }
    if (levels_.size() < static_cast<std::size_t>(depth) + 2)
      levels_.resize(static_cast<std::size_t>(depth) + 2);
    for (int v : branch) {
      const Word* N = g_.row(v);
      Level& next = levels_[static_cast<std::size_t>(depth) + 1];
      next.P.resize(static_cast<std::size_t>(W_));
      next.X.resize(static_cast<std::size_t>(W_));
      for (int w = 0; w < W_; ++w) {
        next.P[static_cast<std::size_t>(w)] = P[static_cast<std::size_t>(w)] & N[w];
        next.X[static_cast<std::size_t>(w)] = X[static_cast<std::size_t>(w)] & N[w];
      }
      R_.push_back(v);
      expand(depth + 1, size + 1);
      R_.pop_back();
      if (budget_.stopped) return;
      P[static_cast<std::size_t>(v / kBits)] &= ~(Word{1} << (v % kBits));
      X[static_cast<std::size_t>(v / kBits)] |= Word{1} << (v % kBits);
    }
  }

  const BitGraph& g_;
  const int W_;
  const int min_size_;
  detail::SearchBudget& budget_;
  std::function<bool(const std::vector<int>&)> report_;  // false: stop
  std::vector<Level> levels_;
  std::vector<int> R_;  // local ids, without the root
};

}  // namespace

bool for_each_maximal_clique(const BitGraph& g, const MaximalCliqueParams& params,
                             const std::function<void(const std::vector<int>&)>& report,
                             long long* nodes) {
  detail::SearchBudget budget;
  budget.deadline = deadline_after(params.time_limit_s);
  const int n = g.size();
  const CoreDecomposition cd = core_decomposition(g);
  const BitGraph h = detail::permuted(g, cd.order);  // id = position in degeneracy order
  std::vector<Word> mask(static_cast<std::size_t>(h.words()), 0);
  std::vector<int> members, clique;
  long long found = 0;
  bool capped = false;
  for (int v = 0; v < n && !budget.stopped; ++v) {
    members.clear();
    detail::for_each_bit(h.row(v), h.words(), [&](int u) { members.push_back(u); });
    const BitGraph local = detail::BranchAndBound::induced(h, members, mask);
    std::vector<Word> P(static_cast<std::size_t>(local.words()), 0), X(P.size(), 0);
    for (std::size_t k = 0; k < members.size(); ++k) {
      auto& S = members[k] > v ? P : X;  // later neighbours extend v; earlier ones were done
      S[k / kBits] |= Word{1} << (k % kBits);
    }
    MaximalCliques enumerate(local, params.min_size, budget, [&](const std::vector<int>& R) {
      clique.assign(1, cd.order[static_cast<std::size_t>(v)]);
      for (int k : R)
        clique.push_back(cd.order[static_cast<std::size_t>(members[static_cast<std::size_t>(k)])]);
      report(clique);
      if (params.max_cliques > 0 && ++found >= params.max_cliques) capped = true;
      return !capped;
    });
    enumerate.run(std::move(P), std::move(X));
  }
  if (nodes) *nodes = budget.nodes;
  return !budget.stopped;
}

}  // namespace verifybench
