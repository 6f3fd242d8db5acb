// BBMC's search (cliques/detail/bbmc.hpp): colouring, re-numbering and infra-chromatic absorption,
// packed subtrees, the interleaved local search, and the recursion.
#include <algorithm>

#include "cliques/detail/bbmc.hpp"
#include "cliques/detail/cover.hpp"
#include "cliques/detail/decomposition.hpp"

namespace verifybench::detail {

void BranchAndBound::run() {
  auto& root = level(0);
  for (int v = 0; v < g_.size(); ++v) root[v / kBits] |= Word{1} << (v % kBits);
  expand(0);
}

int BranchAndBound::colour(const Word* P, int depth, int kmin) {
  auto& ord = order_[static_cast<std::size_t>(depth)];
  auto& col = colour_[static_cast<std::size_t>(depth)];
  if (!recolour_ || infra_) {
    const int size = BitGraph::count(P, W_);
    if (ord.size() < static_cast<std::size_t>(size)) {
      ord.resize(static_cast<std::size_t>(size));
      col.resize(static_cast<std::size_t>(size));
    }
    // The pass reads up to low classes x words per vertex past the bound: past kMaxInfraWords
    // (an incumbent of hundreds in rows of hundreds of words: planted cliques of thousands),
    // it costs more than the branches it saves, so such nodes colour without it; likewise past
    // kMaxInfraPairWords of low classes squared times words (what one vertex can cost).
    const long long low = kmin - 1;
    const int low_classes =
        infra_ && low * W_ <= kMaxInfraWords && low * low * W_ <= kMaxInfraPairWords ? kmin - 1 : 0;
    if (low_classes > 0) {
      classes_.assign(static_cast<std::size_t>(low_classes) * W_, 0);
      frozen_.assign(static_cast<std::size_t>(low_classes), 0);
    }
    const int count =
        colour_kernel(P, W_, g_.row(0), kmin, U_.data(), Q_.data(), ord.data(), col.data(),
                      &colours_, &coloured_, low_classes > 0 ? classes_.data() : nullptr);
    if (low_classes < 2) return count;
    // BBMCX after the fast greedy pass: each vertex past the bound, in colouring order, is
    // re-numbered into or absorbed by the low classes when it can be, and then not branched on.
    // Taking a vertex out of a high class only lowers what later ones could need, so their
    // colours stay valid bounds. After kMaxFailures vertices in a row that neither fit, the rest
    // are kept as they are: past the bound sits a large clique whose members never fit (planted
    // inliers), while DIMACS searches lose almost no pruning (BENCHMARK.md, section 4).
    int kept = 0, failures = 0;
    for (int s = 0; s < count; ++s) {
      const int v = ord[static_cast<std::size_t>(s)];
      if (failures < kMaxFailures) {
        if (renumber_or_absorb(v, low_classes)) {
          failures = 0;
          continue;
        }
        ++failures;
      }
      ord[static_cast<std::size_t>(kept)] = v;
      col[static_cast<std::size_t>(kept)] = col[static_cast<std::size_t>(s)];
      ++kept;
    }
    return kept;
  }
  Word* U = U_.data();
  Word* Q = Q_.data();
  std::copy(P, P + W_, U);
  int k = 0, count = 0, lo = 0, total = 0;
  const int low_classes = kmin - 1;  // classes a vertex may be re-numbered into
  if (low_classes > 0) classes_.assign(static_cast<std::size_t>(low_classes) * W_, 0);
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
        Q[w] &= ~(Word{1} << b);
        const Word* N = g_.row(v);
        ++total;
        if (k >= kmin && low_classes > 1 && renumber(v, low_classes)) continue;
        for (int x = w; x < W_; ++x) Q[x] &= ~N[x];
        if (k <= low_classes) {
          classes_[static_cast<std::size_t>(k - 1) * W_ + static_cast<std::size_t>(w)] |= Word{1}
                                                                                          << b;
        }
        if (k >= kmin) {
          if (static_cast<std::size_t>(count) ==
              ord.size()) {  // grow on demand: deep levels hold few
            ord.resize(std::max<std::size_t>(64, 2 * ord.size()));
            col.resize(ord.size());
          }
          ord[static_cast<std::size_t>(count)] = v;
          col[static_cast<std::size_t>(count)] = k;
          ++count;
        }
      }
    }
  }
  colours_ = k;
  coloured_ = total;
  return count;
}

int BranchAndBound::only_neighbour(const Word* C, const Word* N) const {
  int hits = 0, u = -1;
  for (int x = 0; x < W_ && hits < 2; ++x) {
    const Word both = C[x] & N[x];
    if (!both) continue;
    hits += (both & (both - 1)) ? 2 : 1;
    u = x * kBits + lowest_bit(both);
  }
  return hits == 1 ? u : -1;
}

bool BranchAndBound::renumber(int v, int low_classes) {
  const Word* N = g_.row(v);
  for (int k1 = 0; k1 < low_classes - 1; ++k1) {
    Word* C1 = classes_.data() + static_cast<std::size_t>(k1) * W_;
    const int u = only_neighbour(C1, N);
    if (u < 0) continue;
    const Word* Nu = g_.row(u);
    for (int k2 = k1 + 1; k2 < low_classes; ++k2) {
      Word* C2 = classes_.data() + static_cast<std::size_t>(k2) * W_;
      bool free = true;
      for (int x = 0; x < W_ && free; ++x) free = (C2[x] & Nu[x]) == 0;
      if (!free) continue;
      C1[u / kBits] &= ~(Word{1} << (u % kBits));
      C2[u / kBits] |= Word{1} << (u % kBits);
      C1[v / kBits] |= Word{1} << (v % kBits);
      return true;
    }
  }
  return false;
}

bool BranchAndBound::renumber_or_absorb(int v, int low_classes) {
  const Word* N = g_.row(v);
  for (int i = 0; i < low_classes; ++i) {
    if (frozen_[static_cast<std::size_t>(i)]) continue;
    Word* Ci = classes_.data() + static_cast<std::size_t>(i) * W_;
    const int u = only_neighbour(Ci, N);
    if (u < 0) continue;
    const Word* Nu = g_.row(u);
    for (int j = low_classes - 1; j >= 0; --j) {  // later classes are smaller: try them first
      if (j == i || frozen_[static_cast<std::size_t>(j)]) continue;
      Word* Cj = classes_.data() + static_cast<std::size_t>(j) * W_;
      Word seen = 0, triangle = 0;
      for (int x = 0; x < W_; ++x) {
        const Word a = Cj[x] & Nu[x];
        seen |= a;
        triangle |= a & N[x];
      }
      if (j > i && !seen) {  // Re-NUMBER
        Ci[u / kBits] &= ~(Word{1} << (u % kBits));
        Cj[u / kBits] |= Word{1} << (u % kBits);
        Ci[v / kBits] |= Word{1} << (v % kBits);
        return true;
      }
      if (!triangle) {  // infra-chromatic absorption
        frozen_[static_cast<std::size_t>(i)] = frozen_[static_cast<std::size_t>(j)] = 1;
        return true;
      }
    }
  }
  return false;
}

void BranchAndBound::search_packed(const Word* P, int size) {
  std::vector<int> members;
  for_each_bit(P, W_, [&](int v) { members.push_back(v); });
  if (mask_.empty()) mask_.assign(static_cast<std::size_t>(W_), 0);
  const BitGraph sub = induced(g_, members, mask_);
  BranchAndBound child(sub, best_size_ - size, budget_, recolour_, infra_);
  child.cover_ = cover_;
  child.root_ = root_;
  child.offset_ = offset_ + size;
  --budget_.nodes;  // this node is the child's root
  child.run();
  const int found = static_cast<int>(child.best().size());
  if (found > 0 && size + found > best_size_) {  // the local search may have passed it meanwhile
    best_ = clique_;
    for (int k : child.best()) best_.push_back(members[static_cast<std::size_t>(k)]);
    best_size_ = size + found;
  }
}

bool BranchAndBound::near_clique(const Word* P, int needed) const {
  if (needed < kMinCover) return false;  // small cliques: colouring bounds do well (DIMACS)
  return near_clique(BitGraph::count(P, W_), needed);
}

void BranchAndBound::consult_helper() {
  if (helper_->keep_pace(helper_initial_, helper_share_, work_, best_size_, budget_.deadline)) {
    best_ = helper_->best();
    best_size_ = static_cast<int>(best_.size());
  }
}

void BranchAndBound::expand(int depth) {
  if (!budget_.spend()) return;
  if (root_->helper_ && (budget_.nodes & 1023) == 1) {
    root_->consult_helper();  // the local search runs on the whole graph, in its ids
    best_size_ = std::max(best_size_, root_->best_size_ - offset_);
  }
  Word* P = level(depth).data();
  Word* next = level(depth + 1).data();
  const int size = static_cast<int>(clique_.size());
  if (cover_ && near_clique(P, best_size_ - size + 1)) {
    hand_off_near_clique(g_, P, clique_, best_, best_size_, budget_, cover_scratch_);
    return;
  }
  const int count = colour(P, depth, std::max(1, best_size_ - size + 1));
  root_->work_ += static_cast<long long>(coloured_) * W_;  // packed subtrees count too
  if (colours_ == coloured_) {
    // Every class is a singleton, so each vertex is adjacent to all before it: P is a clique, and
    // C + P is the best of this subtree. Ends the long descent into a large planted clique.
    if (size + coloured_ > best_size_) {
      best_ = clique_;
      for_each_bit(P, W_, [&](int v) { best_.push_back(v); });
      best_size_ = size + coloured_;
    }
    return;
  }
  const auto& ord = order_[static_cast<std::size_t>(depth)];
  const auto& col = colour_[static_cast<std::size_t>(depth)];
  if (depth > 0 && count > 0 && size + col[static_cast<std::size_t>(count) - 1] > best_size_ &&
      worth_packing(coloured_)) {
    search_packed(P, size);
    return;
  }
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
    if (budget_.stopped) return;
    P[v / kBits] &= ~(Word{1} << (v % kBits));
  }
}

}  // namespace verifybench::detail
