// bbmcx-sat's search (cliques/detail/sat_bb.hpp): greedy colouring, Re-NUMBER, and the
// incremental MaxSAT test (unit propagation and failed literals over the colour classes) that
// takes branching vertices out of B.
#include <algorithm>

#include "cliques/detail/cover.hpp"
#include "cliques/detail/sat_bb.hpp"

namespace verifybench::detail {

namespace {
// A node whose low classes span more words than this tests nothing (planted cliques of hundreds
// in long rows: the propagation would cost more than the branches it saves), as in BBMCX.
constexpr long long kMaxSatWords = 4096;
// After this many vertices in a row that stay in B, the rest stay too (a large clique past the
// bound never propagates to a conflict).
constexpr int kMaxFailures = 16;
// Failed literals are tried on low classes of at most this many remaining vertices.
constexpr int kMaxProbeClass = 2;
// Nodes with more branching vertices than this skip the test: each costs a pass over the low
// classes, and a few vertices fewer among many children saves little (p_hat300-3: 1.16 -> 1.01 s).
constexpr int kMaxBranching = 32;
constexpr int kCoverMargin = 16;  // as BranchAndBound::near_clique()

// Counts of remaining vertices saturate at 3: the tests need 0, 1, 2 and "more" only, and a
// portable build has no POPCNT instruction (a library call per word).
constexpr int kMany = 3;
inline int add_bits(int c, Word w) {
  if (!w) return c;
  w &= w - 1;
  if (!w) return std::min(c + 1, kMany);
  return std::min(c + ((w & (w - 1)) ? kMany : 2), kMany);
}

inline void set_bit(Word* b, int v) { b[v / kBits] |= Word{1} << (v % kBits); }
inline void clear_bit(Word* b, int v) { b[v / kBits] &= ~(Word{1} << (v % kBits)); }
}  // namespace

SatBranchAndBound::SatBranchAndBound(const BitGraph& g, int incumbent, SearchBudget& budget)
    : g_(g),
      W_(g.words()),
      best_size_(incumbent),
      budget_(budget),
      levels_(static_cast<std::size_t>(g.size()) + 2),
      order_(levels_.size()),
      colour_(levels_.size()),
      U_(static_cast<std::size_t>(W_)),
      Q_(static_cast<std::size_t>(W_)) {}

void SatBranchAndBound::run() {
  auto& root = levels_[0];
  root.assign(static_cast<std::size_t>(W_), 0);
  for (int v = 0; v < g_.size(); ++v) set_bit(root.data(), v);
  expand(0);
}

int SatBranchAndBound::colour(const Word* P, int depth, int kmin) {
  auto& ord = order_[static_cast<std::size_t>(depth)];
  auto& col = colour_[static_cast<std::size_t>(depth)];
  const int size = BitGraph::count(P, W_);
  if (ord.size() < static_cast<std::size_t>(size)) {
    ord.resize(static_cast<std::size_t>(size));
    col.resize(static_cast<std::size_t>(size));
  }
  const int low = kmin - 1;
  const bool keep_low = low >= 2 && static_cast<long long>(low) * W_ <= kMaxSatWords;
  if (keep_low) classes_.assign(static_cast<std::size_t>(low) * W_, 0);
  return colour_kernel(P, W_, g_.row(0), kmin, U_.data(), Q_.data(), ord.data(), col.data(),
                       &colours_, &coloured_, keep_low ? classes_.data() : nullptr);
}

int SatBranchAndBound::only_neighbour(const Word* C, const Word* N) const {
  int hits = 0, u = -1;
  for (int x = lo_; x < end_ && hits < 2; ++x) {
    const Word both = C[x] & N[x];
    if (!both) continue;
    hits += (both & (both - 1)) ? 2 : 1;
    u = x * kBits + lowest_bit(both);
  }
  return hits == 1 ? u : -1;
}

bool SatBranchAndBound::renumber(int v, int low) {
  const Word* N = g_.row(v);
  for (int k1 = 0; k1 < low - 1; ++k1) {
    if (frozen_[static_cast<std::size_t>(k1)]) continue;
    Word* C1 = classes_.data() + static_cast<std::size_t>(k1) * W_;
    const int u = only_neighbour(C1, N);
    if (u < 0) continue;
    const Word* Nu = g_.row(u);
    for (int k2 = low - 1; k2 > k1; --k2) {  // later classes are smaller: try them first
      if (frozen_[static_cast<std::size_t>(k2)]) continue;
      Word* C2 = classes_.data() + static_cast<std::size_t>(k2) * W_;
      Word seen = 0;
      for (int x = lo_; x < end_ && !seen; ++x) seen = C2[x] & Nu[x];
      if (seen) continue;
      clear_bit(C1, u);
      set_bit(C2, u);
      set_bit(C1, v);
      return true;
    }
  }
  return false;
}

bool SatBranchAndBound::up_reset(int v, int low) {
  const std::size_t rows = static_cast<std::size_t>(low) + 1;
  if (rem_.size() < rows * W_) rem_.resize(rows * W_);
  count_.assign(rows, -1);  // -1: out of the formula (frozen, or the singleton {v} itself)
  unit_of_.assign(rows, -1);
  reason_head_.assign(rows, -1);
  queue_.clear();
  reason_class_.clear();
  reason_next_.clear();
  // v true: every class keeps only v's neighbours. v's singleton never empties (every vertex
  // left is its neighbour), so it takes no part beyond this step, and no reason names it: every
  // subset found holds it.
  const Word* N = g_.row(v);
  for (int k = 0; k < low; ++k) {
    if (frozen_[static_cast<std::size_t>(k)]) continue;
    Word* C = classes_.data() + static_cast<std::size_t>(k) * W_;
    Word* R = rem_.data() + static_cast<std::size_t>(k) * W_;
    int c = 0;
    for (int x = lo_; x < end_; ++x) c = add_bits(c, R[x] = C[x] & N[x]);
    if (c == 0) {  // v fits this class (re-numbering made room): it joins it
      set_bit(C, v);
      return true;
    }
    count_[static_cast<std::size_t>(k)] = c;
    if (c == 1) {
      int u = -1;
      for (int x = lo_; x < end_ && u < 0; ++x)
        if (R[x]) u = x * kBits + lowest_bit(R[x]);
      up_set_unit(k, u);
    }
  }
  return false;
}

void SatBranchAndBound::up_set_unit(int cls, int u) {
  unit_of_[static_cast<std::size_t>(cls)] = u;
  queue_.push_back(cls);
}

int SatBranchAndBound::up_propagate(int low, int from) {
  for (std::size_t qi = static_cast<std::size_t>(from); qi < queue_.size(); ++qi) {
    const int q = queue_[qi];
    const Word* N = g_.row(unit_of_[static_cast<std::size_t>(q)]);
    for (int j = 0; j <= low; ++j) {
      int& c = count_[static_cast<std::size_t>(j)];
      if (j == q || c <= 0) continue;
      Word* R = rem_.data() + static_cast<std::size_t>(j) * W_;
      Word gone = 0;
      for (int x = lo_; x < end_; ++x) gone |= R[x] & ~N[x];
      if (!gone) continue;
      int left = 0;
      for (int x = lo_; x < end_; ++x) left = add_bits(left, R[x] &= N[x]);
      c = left;
      reason_class_.push_back(q);
      reason_next_.push_back(reason_head_[static_cast<std::size_t>(j)]);
      reason_head_[static_cast<std::size_t>(j)] = static_cast<int>(reason_class_.size()) - 1;
      if (left == 0) return j;
      if (left == 1 && unit_of_[static_cast<std::size_t>(j)] < 0) {
        int u = -1;
        for (int x = lo_; x < end_ && u < 0; ++x)
          if (R[x]) u = x * kBits + lowest_bit(R[x]);
        up_set_unit(j, u);
      }
    }
  }
  return -1;
}

void SatBranchAndBound::mark_reasons(int cls, std::vector<char>& marks) {
  std::vector<int>& stack = stack_;
  stack.assign(1, cls);
  marks[static_cast<std::size_t>(cls)] = 1;
  while (!stack.empty()) {
    const int k = stack.back();
    stack.pop_back();
    for (int e = reason_head_[static_cast<std::size_t>(k)]; e >= 0;
         e = reason_next_[static_cast<std::size_t>(e)]) {
      const int q = reason_class_[static_cast<std::size_t>(e)];
      if (!marks[static_cast<std::size_t>(q)]) {
        marks[static_cast<std::size_t>(q)] = 1;
        stack.push_back(q);
      }
    }
  }
}

bool SatBranchAndBound::conflict(int v, int low) {
  if (up_reset(v, low)) return true;
  if (queue_.empty() && kMaxProbeClass < 2) return false;
  const std::size_t rows = static_cast<std::size_t>(low) + 1;
  marks_.assign(rows, 0);
  int empty = up_propagate(low, 0);
  if (empty < 0) {
    // Failed literals: a class of few vertices each of which, set true, propagates to a conflict.
    const std::size_t base_queue = queue_.size(), base_reasons = reason_class_.size();
    for (int j = 0; j < low && empty < 0; ++j) {
      const int c = count_[static_cast<std::size_t>(j)];
      if (c < 2 || c > kMaxProbeClass) continue;
      Word* R = rem_.data() + static_cast<std::size_t>(j) * W_;
      int members[kMaxProbeClass], m = 0;
      for (int x = lo_; x < end_; ++x)
        for (Word y = R[x]; y; y &= y - 1) members[m++] = x * kBits + lowest_bit(y);
      saved_.assign(rem_.begin(), rem_.begin() + static_cast<std::ptrdiff_t>(rows) * W_);
      saved_count_ = count_;
      saved_heads_ = reason_head_;
      marks2_.assign(rows, 0);
      bool all = true;
      for (int i = 0; i < m && all; ++i) {
        std::fill(R + lo_, R + end_, Word{0});
        set_bit(R, members[i]);
        count_[static_cast<std::size_t>(j)] = 1;
        up_set_unit(j, members[i]);
        const int e = up_propagate(low, static_cast<int>(base_queue));
        if (e >= 0) mark_reasons(e, marks2_);
        all = e >= 0;
        // Undo the probe.
        for (std::size_t k = base_queue; k < queue_.size(); ++k)
          unit_of_[static_cast<std::size_t>(queue_[k])] = -1;
        queue_.resize(base_queue);
        reason_class_.resize(base_reasons);
        reason_next_.resize(base_reasons);
        reason_head_ = saved_heads_;
        count_ = saved_count_;
        std::copy(saved_.begin(), saved_.end(), rem_.begin());
      }
      if (all) {
        mark_reasons(j, marks2_);  // and what emptied j down to its probed vertices
        marks_ = marks2_;
        empty = j;
      }
    }
    if (empty < 0) return false;
  } else {
    mark_reasons(empty, marks_);
  }
  for (int k = 0; k < low; ++k)
    if (marks_[static_cast<std::size_t>(k)]) frozen_[static_cast<std::size_t>(k)] = 1;
  return true;
}

int SatBranchAndBound::filter(int depth, int count, int low) {
  auto& ord = order_[static_cast<std::size_t>(depth)];
  auto& col = colour_[static_cast<std::size_t>(depth)];
  frozen_.assign(static_cast<std::size_t>(low), 0);
  int kept = 0, failures = 0;
  for (int s = 0; s < count; ++s) {
    const int v = ord[static_cast<std::size_t>(s)];
    if (failures < kMaxFailures) {
      if (renumber(v, low) || conflict(v, low)) {
        failures = 0;
        ++absorbed_;
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

void SatBranchAndBound::search_cover(const Word* P, int size) {
  std::vector<int> members;
  for_each_bit(P, W_, [&](int v) { members.push_back(v); });
  const BitGraph sub = permuted(g_, members, budget_.deadline);
  CoverSearch cover(sub, best_size_ - size, budget_);
  cover.run();
  const int found = static_cast<int>(cover.best().size());
  if (found > 0 && size + found > best_size_) {
    best_ = clique_;
    for (int k : cover.best()) best_.push_back(members[static_cast<std::size_t>(k)]);
    best_size_ = size + found;
  }
}

void SatBranchAndBound::expand(int depth) {
  if (!budget_.spend()) return;
  auto& next_level = levels_[static_cast<std::size_t>(depth) + 1];
  if (next_level.empty()) next_level.assign(static_cast<std::size_t>(W_), 0);
  Word* P = levels_[static_cast<std::size_t>(depth)].data();
  Word* next = next_level.data();
  const int size = static_cast<int>(clique_.size());
  const int needed = best_size_ - size + 1;
  if (cover_min_ > 0 && needed >= cover_min_ &&
      BitGraph::count(P, W_) < 2 * needed + kCoverMargin) {
    search_cover(P, size);
    return;
  }
  const int kmin = std::max(1, needed);
  const int count = colour(P, depth, kmin);
  if (colours_ == coloured_) {  // every class a singleton: P is a clique
    if (size + coloured_ > best_size_) {
      best_ = clique_;
      for_each_bit(P, W_, [&](int v) { best_.push_back(v); });
      best_size_ = size + coloured_;
    }
    return;
  }
  const int low = kmin - 1;
  int branch = count;
  if (count > 0 && count <= kMaxBranching && low >= 2 &&
      static_cast<long long>(low) * W_ <= kMaxSatWords) {
    lo_ = 0;
    end_ = W_;
    while (lo_ < end_ && P[lo_] == 0) ++lo_;
    while (end_ > lo_ && P[end_ - 1] == 0) --end_;
    branch = filter(depth, count, low);
  }
  const auto& ord = order_[static_cast<std::size_t>(depth)];
  const auto& col = colour_[static_cast<std::size_t>(depth)];
  for (int i = branch - 1; i >= 0; --i) {
    // A, the vertices not branched on, holds no clique above `low`; B's first i + 1 vertices none
    // above their colour count, nor above i + 1.
    const int bound = std::min(col[static_cast<std::size_t>(i)], low + i + 1);
    if (size + bound <= best_size_) return;
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
    clear_bit(P, v);
  }
}

}  // namespace verifybench::detail
