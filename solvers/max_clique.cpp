#include "solvers/max_clique.hpp"

#include <algorithm>
#include <chrono>

#include "solvers/timer.hpp"

namespace verifybench {

namespace {

using Word = BitGraph::Word;
using Clock = SteadyClock;
constexpr int kBits = BitGraph::kWordBits;

inline int lowest_bit(Word w) { return __builtin_ctzll(w); }

/// Calls f(v) for every set bit of a bitset of `words` words, in increasing order.
template <class F>
void for_each_bit(const Word* bits, int words, F&& f) {
  for (int w = 0; w < words; ++w) {
    for (Word x = bits[w]; x; x &= x - 1) f(w * kBits + lowest_bit(x));
  }
}

/// Greedy clique from every vertex whose core number could beat the incumbent: repeatedly add the
/// candidate of highest core number. Gives the lower bound that prunes the exact search.
std::vector<int> greedy_clique(const BitGraph& g, const CoreDecomposition& cd) {
  const int W = g.words();
  std::vector<int> best, clique;
  std::vector<Word> cand(static_cast<std::size_t>(W));
  for (auto it = cd.order.rbegin(); it != cd.order.rend(); ++it) {
    const int v = *it;
    if (cd.core[v] + 1 <= static_cast<int>(best.size())) continue;
    clique.assign(1, v);
    std::copy(g.row(v), g.row(v) + W, cand.begin());
    for (;;) {
      int pick = -1;
      for_each_bit(cand.data(), W, [&](int u) {
        if (pick < 0 || cd.core[u] > cd.core[pick]) pick = u;
      });
      if (pick < 0) break;
      clique.push_back(pick);
      const Word* row = g.row(pick);
      for (int w = 0; w < W; ++w) cand[w] &= row[w];
    }
    if (clique.size() > best.size()) best = clique;
  }
  return best;
}

/// BBMC: branch on vertices in reverse greedy-colour order; prune when |C| + colour <= |best|.
class BranchAndBound {
 public:
  BranchAndBound(const BitGraph& g, int incumbent, int max_depth, Clock::time_point deadline,
                 long long node_limit)
      : g_(g), W_(g.words()), best_size_(incumbent), deadline_(deadline), node_limit_(node_limit),
        levels_(static_cast<std::size_t>(max_depth) + 2), order_(levels_.size()),
        colour_(levels_.size()), U_(static_cast<std::size_t>(W_)), Q_(static_cast<std::size_t>(W_)) {}

  void run() {
    auto& root = level(0);
    for (int v = 0; v < g_.size(); ++v) root[v / kBits] |= Word{1} << (v % kBits);
    expand(0);
  }
  const std::vector<int>& best() const { return best_; }
  bool stopped() const { return stopped_; }
  long long nodes() const { return nodes_; }

 private:
  std::vector<Word>& level(int depth) {
    auto& l = levels_[static_cast<std::size_t>(depth)];
    if (l.empty()) l.assign(static_cast<std::size_t>(W_), 0);
    return l;
  }

  // Bit-parallel greedy colouring of P; stores only vertices of colour >= kmin, since the rest can
  // never pass the bound (BBMC's colour-class pruning). Returns how many were stored.
  int colour(const Word* P, int depth, int kmin) {
    auto& ord = order_[static_cast<std::size_t>(depth)];
    auto& col = colour_[static_cast<std::size_t>(depth)];
    if (ord.empty()) {
      ord.resize(static_cast<std::size_t>(g_.size()));
      col.resize(static_cast<std::size_t>(g_.size()));
    }
    Word* U = U_.data();
    Word* Q = Q_.data();
    std::copy(P, P + W_, U);
    int k = 0, count = 0, lo = 0;
    for (;;) {
      while (lo < W_ && U[lo] == 0) ++lo;
      if (lo == W_) break;
      ++k;
      std::copy(U + lo, U + W_, Q + lo);
      for (int w = lo; w < W_; ++w) {
        while (Q[w]) {
          const int b = lowest_bit(Q[w]);
          const int v = w * kBits + b;
          U[w] &= ~(Word{1} << b);
          const Word* N = g_.row(v);
          Q[w] &= ~(Word{1} << b);
          for (int x = w; x < W_; ++x) Q[x] &= ~N[x];
          if (k >= kmin) {
            ord[static_cast<std::size_t>(count)] = v;
            col[static_cast<std::size_t>(count)] = k;
            ++count;
          }
        }
      }
    }
    return count;
  }

  void expand(int depth) {
    if ((++nodes_ & 63) == 1 || node_limit_ > 0) {
      if ((node_limit_ > 0 && nodes_ >= node_limit_) || Clock::now() >= deadline_) stopped_ = true;
    }
    if (stopped_) return;
    Word* P = level(depth).data();
    Word* next = level(depth + 1).data();
    const int size = static_cast<int>(clique_.size());
    const int count = colour(P, depth, std::max(1, best_size_ - size + 1));
    const auto& ord = order_[static_cast<std::size_t>(depth)];
    const auto& col = colour_[static_cast<std::size_t>(depth)];
    for (int i = count - 1; i >= 0; --i) {
      if (size + col[static_cast<std::size_t>(i)] <= best_size_) return;
      const int v = ord[static_cast<std::size_t>(i)];
      const Word* N = g_.row(v);
      Word any = 0;
      for (int w = 0; w < W_; ++w) any |= (next[w] = P[w] & N[w]);
      clique_.push_back(v);
      if (!any) {
        if (size + 1 > best_size_) {
          best_ = clique_;
          best_size_ = size + 1;
        }
      } else {
        expand(depth + 1);
      }
      clique_.pop_back();
      if (stopped_) return;
      P[v / kBits] &= ~(Word{1} << (v % kBits));
    }
  }

  const BitGraph& g_;
  const int W_;
  int best_size_;
  Clock::time_point deadline_;
  long long node_limit_;
  long long nodes_ = 0;
  bool stopped_ = false;
  std::vector<int> clique_, best_;
  std::vector<std::vector<Word>> levels_;  // candidate set per depth
  std::vector<std::vector<int>> order_, colour_;
  std::vector<Word> U_, Q_;
};

}  // namespace

CoreDecomposition core_decomposition(const BitGraph& g) {
  const int n = g.size();
  CoreDecomposition cd;
  std::vector<int> deg(static_cast<std::size_t>(n)), pos(static_cast<std::size_t>(n)),
      vert(static_cast<std::size_t>(n));
  int max_deg = 0;
  for (int v = 0; v < n; ++v) max_deg = std::max(max_deg, deg[v] = g.degree(v));
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
  if (max_deg >= 0 && !bin.empty()) bin[0] = 0;
  for (int i = 0; i < n; ++i) {
    const int v = vert[i];
    for_each_bit(g.row(v), g.words(), [&](int u) {
      if (deg[u] > deg[v]) {
        const int du = deg[u], pu = pos[u], pw = bin[du], w = vert[pw];
        if (u != w) {
          std::swap(vert[pu], vert[pw]);
          pos[u] = pw;
          pos[w] = pu;
        }
        ++bin[du];
        --deg[u];
      }
    });
  }
  cd.core = std::move(deg);
  cd.order = std::move(vert);
  return cd;
}

CliqueSearchResult max_clique(const BitGraph& g, const CliqueSearchParams& params) {
  const auto deadline = deadline_after(params.time_limit_s);
  CliqueSearchResult result;
  if (g.size() == 0) {
    result.optimal = true;
    return result;
  }
  const CoreDecomposition cd = core_decomposition(g);
  const int max_core = *std::max_element(cd.core.begin(), cd.core.end());
  result.upper_bound = max_core + 1;
  result.clique = greedy_clique(g, cd);
  const int incumbent = static_cast<int>(result.clique.size());

  if (incumbent < result.upper_bound) {
    // A clique larger than the incumbent lies in the incumbent-core: keep those vertices, the
    // highest core first (the initial order BBMC's colouring wants).
    std::vector<int> kept;
    for (auto it = cd.order.rbegin(); it != cd.order.rend(); ++it) {
      if (cd.core[*it] >= incumbent) kept.push_back(*it);
    }
    std::vector<int> index(static_cast<std::size_t>(g.size()), -1);
    for (std::size_t k = 0; k < kept.size(); ++k) index[kept[k]] = static_cast<int>(k);
    BitGraph sub(static_cast<int>(kept.size()));
    for (std::size_t k = 0; k < kept.size(); ++k) {
      for_each_bit(g.row(kept[k]), g.words(), [&](int u) {
        if (index[u] > static_cast<int>(k)) sub.add_edge(static_cast<int>(k), index[u]);
      });
    }
    BranchAndBound bb(sub, incumbent, max_core + 1, deadline, params.node_limit);
    bb.run();
    result.nodes = bb.nodes();
    result.optimal = !bb.stopped();
    if (!bb.best().empty()) {
      result.clique.clear();
      for (int k : bb.best()) result.clique.push_back(kept[static_cast<std::size_t>(k)]);
    }
  } else {
    result.optimal = true;
  }
  std::sort(result.clique.begin(), result.clique.end());
  return result;
}

}  // namespace verifybench
