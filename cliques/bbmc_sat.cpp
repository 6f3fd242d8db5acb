// bbmcx-sat's search (cliques/detail/sat_bb.hpp): greedy colouring, Re-NUMBER, and the
// incremental MaxSAT test (unit propagation over the colour classes) that
// takes branching vertices out of B.
#include <algorithm>

#include "cliques/detail/cover.hpp"
#include "cliques/detail/sat_bb.hpp"
#include "core/detail/multiversion.hpp"

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
// frozen_: a class in an inconsistent subset found for an earlier colour group (out of the tests),
// or for the current one (pending: still in its tests, but taking no vertex in).
constexpr char kPending = 2, kFrozen = 1;
// SatOptions::relax: a class of a relaxed subset stays in the tests but takes no vertex in.
constexpr char kRelaxed = 3;
// Re-NUMBER looks for a class without u's neighbours by testing the classes from the last down;
// past this many passes over the node's words (plus 8) it counts u's non-neighbours per class
// instead, when they are at most kMaxStrangers.
constexpr int kTestPasses = 2;
constexpr int kMaxStrangers = 64;

// The union of the `low` classes (words [lo, end) of W each) into A, and each class's size.
VB_MULTIVERSION_POPCNT
void union_and_sizes(const Word* classes, int low, int W, int lo, int end, Word* A, int* sizes) {
  for (int k = 0; k < low; ++k) {
    const Word* C = classes + static_cast<std::size_t>(k) * W;
    int members = 0;
    for (int x = lo; x < end; ++x) {
      A[x] |= C[x];
      members += __builtin_popcountll(C[x]);
    }
    sizes[k] = members;
  }
}

// |a & ~b| over words [lo, end).
VB_MULTIVERSION_POPCNT
int count_and_not(const Word* a, const Word* b, int lo, int end) {
  int n = 0;
  for (int x = lo; x < end; ++x) n += __builtin_popcountll(a[x] & ~b[x]);
  return n;
}

inline void set_bit(Word* b, int v) { b[v / kBits] |= Word{1} << (v % kBits); }
inline void clear_bit(Word* b, int v) { b[v / kBits] &= ~(Word{1} << (v % kBits)); }
}  // namespace

SatBranchAndBound::SatBranchAndBound(const BitGraph& g, int incumbent, SearchBudget& budget,
                                     SatOptions options)
    : g_(g),
      W_(g.words()),
      best_size_(incumbent),
      budget_(budget),
      options_(options),
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
  if (keep_low) {
    classes_.assign(static_cast<std::size_t>(low) * W_, 0);
    if (class_of_.size() < static_cast<std::size_t>(g_.size()))
      class_of_.assign(static_cast<std::size_t>(g_.size()), -1);
  }
  // The kernel records each low vertex's class as it colours it (index_classes() reads them).
  return colour_kernel(P, W_, g_.row(0), kmin, U_.data(), Q_.data(), ord.data(), col.data(),
                       &colours_, &coloured_, keep_low ? classes_.data() : nullptr,
                       keep_low ? class_of_.data() : nullptr);
}

void SatBranchAndBound::index_classes(int low) {
  // class_of_ was written by the colouring (colour()) for every vertex of A; only A's are read.
  A_.assign(static_cast<std::size_t>(W_), 0);
  open_.resize(static_cast<std::size_t>(low));
  union_and_sizes(classes_.data(), low, W_, lo_, end_, A_.data(), open_.data());
  L_ = A_;
  R_.assign(static_cast<std::size_t>(W_), 0);
  count_.resize(static_cast<std::size_t>(low));
  marks_.assign(static_cast<std::size_t>(low), 0);
  marked_.clear();
  unit_of_.assign(static_cast<std::size_t>(low), 0);
  reason_head_.assign(static_cast<std::size_t>(low), -1);
  classes_count_ = low;
  pend_.assign(static_cast<std::size_t>(low), 0);
  if (options_.relax) {
    if (literals_of_.size() < static_cast<std::size_t>(low)) literals_of_.resize(low);
    for (int k = 0; k < low; ++k) literals_of_[static_cast<std::size_t>(k)].clear();
    classes_of_.clear();
    literal_set_.clear();
    literals_set_.clear();
    group_refuted_.clear();
  }
}

void SatBranchAndBound::join(int v, int k) {
  set_bit(classes_.data() + static_cast<std::size_t>(k) * W_, v);
  set_bit(A_.data(), v);
  set_bit(L_.data(), v);
  class_of_[static_cast<std::size_t>(v)] = k;
  ++open_[static_cast<std::size_t>(k)];  // only free classes take vertices in
}

int SatBranchAndBound::member(int k) const {
  const Word* C = classes_.data() + static_cast<std::size_t>(k) * W_;
  for (int x = lo_; x < end_; ++x)
    if (const Word y = C[x] & R_[static_cast<std::size_t>(x)]) return x * kBits + lowest_bit(y);
  return -1;
}

int SatBranchAndBound::neighbour_word(int u, int k) const {
  const Word* Nu = g_.row(u);
  const Word* C = classes_.data() + static_cast<std::size_t>(k) * W_;
  int x = lo_;
  while (x < end_ && (C[x] & Nu[x]) == 0) ++x;
  return x;
}

int SatBranchAndBound::last_class_without(int u, int k1, int low) {
  // Testing a class reads u's row up to the first neighbour it holds: one word or a few where the
  // first class tested has none (sparse nodes, p_hat1000-1), but on a dense node u has a neighbour
  // in nearly every class (144 classes tested a call on balm_realworld's b112_72 FPFH 0.3 k3).
  // There a class holds none of u's neighbours when all its members are among u's few
  // non-neighbours: counting those per class costs two passes over the row (one counts them, one
  // files them by class).
  const Word* Nu = g_.row(u);
  int top = low - 1;
  int budget = kTestPasses * (end_ - lo_) + 8;  // words the tests may read
  for (; top > k1; --top) {
    if (frozen_[static_cast<std::size_t>(top)]) continue;
    const int x = neighbour_word(u, top);
    if (x == end_) return top;
    budget -= x - lo_ + 1;
    if (budget <= 0) break;
  }
  if (--top <= k1) return k1;
  if (count_and_not(A_.data(), Nu, lo_, end_) > kMaxStrangers) {
    // Many non-neighbours: the rest tested one by one.
    while (top > k1 && (frozen_[static_cast<std::size_t>(top)] || neighbour_word(u, top) < end_))
      --top;
    return top;
  }
  if (hits_.size() < static_cast<std::size_t>(classes_count_))
    hits_.resize(static_cast<std::size_t>(classes_count_), 0);
  touched_.clear();
  for (int x = lo_; x < end_; ++x) {
    for (Word y = A_[static_cast<std::size_t>(x)] & ~Nu[x]; y; y &= y - 1) {
      const int k = class_of_[static_cast<std::size_t>(x * kBits + lowest_bit(y))];
      if (hits_[static_cast<std::size_t>(k)]++ == 0) touched_.push_back(k);
    }
  }
  int k2 = k1;
  for (const int k : touched_) {
    const auto ks = static_cast<std::size_t>(k);
    if (k > k2 && k <= top && !frozen_[ks] && hits_[ks] == open_[ks]) k2 = k;
    hits_[ks] = 0;
  }
  return k2;
}

bool SatBranchAndBound::renumber(int v, int low) {
  const Word* N = g_.row(v);
  for (int i = 0; i < ones_count_; ++i) {  // the classes where v has one neighbour
    const int k1 = ones_[static_cast<std::size_t>(i)];
    if (k1 >= low - 1) break;
    if (frozen_[static_cast<std::size_t>(k1)]) continue;  // shared: it takes no vertex in
    Word* C1 = classes_.data() + static_cast<std::size_t>(k1) * W_;
    int u = -1;
    for (int x = lo_; x < end_ && u < 0; ++x)
      if (const Word both = C1[x] & N[x]) u = x * kBits + lowest_bit(both);
    // The last unfrozen class k2 > k1 where u has no neighbour.
    const int k2 = last_class_without(u, k1, low);
    if (k2 == k1) continue;
    clear_bit(C1, u);
    --open_[static_cast<std::size_t>(k1)];
    join(u, k2);
    join(v, k1);
    return true;
  }
  return false;
}

void SatBranchAndBound::up_set_unit(int cls) {
  unit_of_[static_cast<std::size_t>(cls)] = 1;
  queue_.push_back(cls);
}

inline bool SatBranchAndBound::lose_member(int j, int q) {
  int& c = count_[static_cast<std::size_t>(j)];
  --c;
  int& head = reason_head_[static_cast<std::size_t>(j)];
  if (head < 0 || reason_class_[static_cast<std::size_t>(head)] != q) {
    reason_class_.push_back(q);
    reason_owner_.push_back(j);
    reason_next_.push_back(head);
    head = static_cast<int>(reason_class_.size()) - 1;
  }
  if (c == 0) return true;
  if (c == 1 && !unit_of_[static_cast<std::size_t>(j)]) up_set_unit(j);
  return false;
}

int SatBranchAndBound::up_propagate(std::size_t from) {
  return options_.relax ? propagate<true>(from) : propagate<false>(from);
}

template <bool kRelax>
int SatBranchAndBound::propagate(std::size_t from) {
  for (std::size_t qi = from; qi < queue_.size(); ++qi) {
    if constexpr (kRelax) {
      // Used first (CliSAT, LMC): a unit among the classes earlier subsets hold goes before the
      // others, so a conflict reuses them and leaves fresh classes for the later tests.
      for (std::size_t j = qi; j < queue_.size(); ++j) {
        if (frozen_[static_cast<std::size_t>(queue_[j])]) {
          std::swap(queue_[qi], queue_[j]);
          break;
        }
      }
    }
    const int q = queue_[qi];
    const int u = member(q);  // the class's one member left: it is set true
    if constexpr (kRelax) {
      if (u < 0) {  // ... a relaxation literal
        int emptied = -1;
        if (fix_literal(q, emptied)) return emptied;
        continue;
      }
    }
    const Word* N = g_.row(u);
    // u true: each of its non-neighbours leaves its class (u stays: a later unit that is not its
    // neighbour empties q).
    for (int x = lo_; x < end_; ++x) {
      Word& R = R_[static_cast<std::size_t>(x)];
      Word gone = R & ~N[x];
      if (x == u / kBits) gone &= ~(Word{1} << (u % kBits));
      R &= ~gone;
      for (; gone; gone &= gone - 1) {
        const int j = class_of_[static_cast<std::size_t>(x * kBits + lowest_bit(gone))];
        if (lose_member(j, q)) return j;
      }
    }
  }
  return -1;
}

bool SatBranchAndBound::fix_literal(int q, int& emptied) {
  int d = -1;
  for (int l : literals_of_[static_cast<std::size_t>(q)]) {
    if (literal_set_[static_cast<std::size_t>(l)] < 0) {
      d = l;
      break;
    }
  }
  if (d < 0) return false;
  literal_set_[static_cast<std::size_t>(d)] = q;
  literals_set_.push_back(d);
  // At most one class of the subset is satisfied by d: it leaves the others.
  for (int j : classes_of_[static_cast<std::size_t>(d)]) {
    if (j != q && lose_member(j, q)) {
      emptied = j;
      return true;
    }
  }
  return false;
}

void SatBranchAndBound::mark_reasons(int cls, std::vector<char>& marks) {
  std::vector<int>& stack = stack_;
  stack.assign(1, cls);
  if (!marks[static_cast<std::size_t>(cls)]) marked_.push_back(cls);
  marks[static_cast<std::size_t>(cls)] = 1;
  while (!stack.empty()) {
    const int k = stack.back();
    stack.pop_back();
    for (int e = reason_head_[static_cast<std::size_t>(k)]; e >= 0;
         e = reason_next_[static_cast<std::size_t>(e)]) {
      const int q = reason_class_[static_cast<std::size_t>(e)];
      if (!marks[static_cast<std::size_t>(q)]) {
        marks[static_cast<std::size_t>(q)] = 1;
        marked_.push_back(q);
        stack.push_back(q);
      }
    }
  }
}

bool SatBranchAndBound::test(int v, int low) {
  // v true: every class keeps only v's neighbours. v's singleton never empties (every vertex
  // left is its neighbour), so no reason names it: every subset found holds it.
  const int classes = classes_count_;  // the low classes and the relaxed groups' (relax)
  std::copy(open_.begin(), open_.begin() + classes, count_.begin());
  const Word* N = g_.row(v);
  for (int x = lo_; x < end_; ++x) {
    const Word L = L_[static_cast<std::size_t>(x)];
    R_[static_cast<std::size_t>(x)] = L & N[x];
    for (Word y = L & ~N[x]; y; y &= y - 1) {
      const int w = x * kBits + lowest_bit(y);
      --count_[static_cast<std::size_t>(class_of_[static_cast<std::size_t>(w)])];
    }
  }
  // The classes v empties (v fits the first: re-numbering made room) and those it leaves one.
  // Branch-free on the classes left one member (a data-dependent branch there cost a fifth of
  // the test); the first empty class ends the loop.
  if (ones_.size() < static_cast<std::size_t>(classes))
    ones_.resize(static_cast<std::size_t>(classes));
  int* ones = ones_.data();
  int m = 0;
  for (int k = 0; k < classes; ++k) {
    const int c = count_[static_cast<std::size_t>(k)];
    ones[m] = k;
    m += c == 1;
    if (c == 0) {
      // A free class takes v; a pending one is an inconsistent subset with v by itself.
      if (!frozen_[static_cast<std::size_t>(k)]) {
        join(v, k);
      } else if (options_.relax) {
        group_refuted_.push_back(v);
      }
      return true;
    }
  }
  ones_count_ = m;
  bool out = options_.renumber && renumber(v, low);
  if (!out) {
    for (int i = 0; i < ones_count_; ++i) up_set_unit(ones_[static_cast<std::size_t>(i)]);
    out = conflict(low);
    if (options_.relax) {
      if (out) group_refuted_.push_back(v);
      for (int d : literals_set_) literal_set_[static_cast<std::size_t>(d)] = -1;
      literals_set_.clear();
    }
    for (int k : queue_) unit_of_[static_cast<std::size_t>(k)] = 0;
    queue_.clear();
    for (int k : reason_owner_) reason_head_[static_cast<std::size_t>(k)] = -1;
    reason_class_.clear();
    reason_owner_.clear();
    reason_next_.clear();
  }
  return out;
}

int SatBranchAndBound::failed_literal(int low) {
  const std::size_t base_queue = queue_.size(), base_reasons = reason_class_.size();
  const std::size_t base_literals = literals_set_.size();
  saved_R_.assign(R_.begin(), R_.end());
  saved_count_.assign(count_.begin(), count_.end());
  for (int j = 0; j < low; ++j) {
    const int c = count_[static_cast<std::size_t>(j)];
    if (c < 2 || c > kMaxProbeClass) continue;
    if (options_.relax && !literals_of_[static_cast<std::size_t>(j)].empty()) continue;
    int members[kMaxProbeClass], m = 0;
    const Word* C = classes_.data() + static_cast<std::size_t>(j) * W_;
    for (int x = lo_; x < end_; ++x)
      for (Word y = C[x] & R_[static_cast<std::size_t>(x)]; y; y &= y - 1)
        members[m++] = x * kBits + lowest_bit(y);
    clear_marks();
    bool all = true;
    for (int i = 0; i < m && all; ++i) {
      // members[i] alone left in class j, set true.
      for (int o = 0; o < m; ++o)
        if (o != i) clear_bit(R_.data(), members[o]);
      count_[static_cast<std::size_t>(j)] = 1;
      up_set_unit(j);
      const int e = up_propagate(base_queue);
      if (e >= 0) mark_reasons(e, marks_);
      all = e >= 0;
      // Undo the probe.
      for (std::size_t k = base_literals; k < literals_set_.size(); ++k)
        literal_set_[static_cast<std::size_t>(literals_set_[k])] = -1;
      literals_set_.resize(base_literals);
      for (std::size_t k = base_queue; k < queue_.size(); ++k)
        unit_of_[static_cast<std::size_t>(queue_[k])] = 0;
      queue_.resize(base_queue);
      for (std::size_t e2 = reason_class_.size(); e2-- > base_reasons;)
        reason_head_[static_cast<std::size_t>(reason_owner_[e2])] = reason_next_[e2];
      reason_class_.resize(base_reasons);
      reason_owner_.resize(base_reasons);
      reason_next_.resize(base_reasons);
      std::copy(saved_R_.begin(), saved_R_.end(), R_.begin());
      std::copy(saved_count_.begin(), saved_count_.end(), count_.begin());
    }
    if (all) {
      mark_reasons(j, marks_);  // and what emptied j down to its probed vertices
      return j;
    }
  }
  return -1;
}

bool SatBranchAndBound::conflict(int low) {
  int empty = up_propagate(0);
  if (empty >= 0) {
    clear_marks();
    mark_reasons(empty, marks_);
  } else if (!options_.failed_literals || (empty = failed_literal(low)) < 0) {
    return false;
  }
  for (int k : marked_) {
    if (pend_[static_cast<std::size_t>(k)]) continue;
    pend_[static_cast<std::size_t>(k)] = 1;
    // Frozen (or relaxed) once v's colour group is done; until then it takes no vertex in.
    if (!frozen_[static_cast<std::size_t>(k)]) frozen_[static_cast<std::size_t>(k)] = kPending;
    pending_.push_back(k);
  }
  return true;
}

void SatBranchAndBound::clear_marks() {
  for (int k : marked_) marks_[static_cast<std::size_t>(k)] = 0;
  marked_.clear();
}

void SatBranchAndBound::freeze_pending() {
  for (int k : pending_) {
    frozen_[static_cast<std::size_t>(k)] = kFrozen;  // its members take no part in later tests
    open_[static_cast<std::size_t>(k)] = -1;
    const Word* C = classes_.data() + static_cast<std::size_t>(k) * W_;
    for (int x = lo_; x < end_; ++x) L_[static_cast<std::size_t>(x)] &= ~C[x];
    pend_[static_cast<std::size_t>(k)] = 0;
  }
  pending_.clear();
  group_refuted_.clear();
}

void SatBranchAndBound::relax_pending() {
  if (pending_.empty()) {
    group_refuted_.clear();
    return;
  }
  // The group's refuted vertices become a class (pairwise non-adjacent: one colour group).
  const int x = classes_count_++;
  const auto xs = static_cast<std::size_t>(x);
  classes_.resize(static_cast<std::size_t>(classes_count_) * W_, 0);
  Word* C = classes_.data() + xs * W_;
  for (int v : group_refuted_) {
    set_bit(C, v);
    set_bit(L_.data(), v);
    class_of_[static_cast<std::size_t>(v)] = x;
  }
  open_.push_back(static_cast<int>(group_refuted_.size()));
  count_.push_back(0);
  marks_.push_back(0);
  unit_of_.push_back(0);
  reason_head_.push_back(-1);
  frozen_.push_back(kRelaxed);
  pend_.push_back(0);
  if (literals_of_.size() <= xs) literals_of_.resize(xs + 1);
  literals_of_[xs].clear();
  pending_.push_back(x);
  // One literal shared by the subset's classes, each of which counts it as a member.
  const int d = static_cast<int>(classes_of_.size());
  classes_of_.push_back(pending_);
  literal_set_.push_back(-1);
  for (int k : pending_) {
    literals_of_[static_cast<std::size_t>(k)].push_back(d);
    ++open_[static_cast<std::size_t>(k)];
    frozen_[static_cast<std::size_t>(k)] = kRelaxed;
    pend_[static_cast<std::size_t>(k)] = 0;
  }
  pending_.clear();
  group_refuted_.clear();
  ++relaxed_;
}

int SatBranchAndBound::filter(int depth, int count, int low) {
  auto& ord = order_[static_cast<std::size_t>(depth)];
  auto& col = colour_[static_cast<std::size_t>(depth)];
  frozen_.assign(static_cast<std::size_t>(low), 0);
  pending_.clear();
  index_classes(low);
  int kept = 0, failures = 0;
  for (int s = 0; s < count; ++s) {
    const int v = ord[static_cast<std::size_t>(s)];
    if (s > 0 && col[static_cast<std::size_t>(s)] != col[static_cast<std::size_t>(s) - 1]) {
      if (options_.relax) {
        relax_pending();
      } else {
        freeze_pending();
      }
    }
    if (failures < kMaxFailures) {
      if (test(v, low)) {
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

void SatBranchAndBound::consult_helper() {
  if (helper_->keep_pace(helper_initial_, helper_share_, work_, best_size_, budget_.deadline)) {
    best_ = helper_->best();
    best_size_ = static_cast<int>(best_.size());
  }
}

void SatBranchAndBound::expand(int depth) {
  if (!budget_.spend()) return;
  if (helper_ && (budget_.nodes & 1023) == 1) consult_helper();
  auto& next_level = levels_[static_cast<std::size_t>(depth) + 1];
  if (next_level.empty()) next_level.assign(static_cast<std::size_t>(W_), 0);
  Word* P = levels_[static_cast<std::size_t>(depth)].data();
  Word* next = next_level.data();
  const int size = static_cast<int>(clique_.size());
  const int needed = best_size_ - size + 1;
  if (cover_min_ > 0 && needed >= cover_min_ &&
      BitGraph::count(P, W_) < 2 * needed + BranchAndBound::kCoverMargin) {
    hand_off_near_clique(g_, P, clique_, best_, best_size_, budget_, cover_scratch_);
    return;
  }
  const int kmin = std::max(1, needed);
  const int count = colour(P, depth, kmin);
  work_ += static_cast<long long>(coloured_) * W_;
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
