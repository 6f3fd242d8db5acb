// The vertex-cover search of cliques/detail/cover.hpp.
#include "cliques/detail/cover.hpp"

#include <algorithm>

#include "cliques/detail/decomposition.hpp"

namespace verifybench::detail {

namespace {
// The LP bound is at least half the vertices left: while they are more than twice what a better
// set needs (plus this margin), a matching pass can neither prune nor, as a rule, reduce.
constexpr int kLpMargin = 16;

// A node whose live vertices are at most 1/kPackRatio of the graph (and at least kMinPacked)
// searches on them packed.
constexpr int kPackRatio = 3;
constexpr int kMinPacked = 32;

// Cycles of the matching this short are checked for being cliques of H (a clique of k vertices
// needs k - 1 of them in a cover, not ceil(k / 2)); longer ones rarely are.
constexpr int kMaxCliqueCycle = 16;

// A search keeps its lists' live parts first (go_live()) once it has branched this many times:
// a deep search scans mostly removed vertices otherwise, a short one would pay the set-up.
constexpr int kLiveAfter = 32;
}  // namespace

CoverSearch::CoverSearch(const BitGraph& g, int incumbent, SearchBudget& budget)
    : g_(g),
      n_(g.size()),
      best_size_(incumbent),
      budget_(budget),
      root_upper_(g.size()),
      off_(static_cast<std::size_t>(n_) + 1, 0),
      alive_(static_cast<std::size_t>(n_), 1),
      deg_(static_cast<std::size_t>(n_), 0),
      alive_count_(n_),
      mate_l_(static_cast<std::size_t>(n_), -1),
      mate_r_(static_cast<std::size_t>(n_), -1),
      dist_(static_cast<std::size_t>(n_), -1),
      iter_(static_cast<std::size_t>(n_), 0),
      z_r_(static_cast<std::size_t>(n_), 0),
      seen_(static_cast<std::size_t>(n_), 0) {
  const int W = g.words();
  // H's lists are sized first (a vertex's degree in H is n - 1 - its degree in g), so that they
  // are written once: grown by push_back, their copies and page faults were a third of a search
  // that hands thousands of near-clique nodes over (BENCHMARK.md section 19).
  std::size_t total = 0;
  for (int v = 0; v < n_; ++v) total += static_cast<std::size_t>(n_ - 1 - g.degree(v));
  nbr_.reserve(total);
  for (int v = 0; v < n_; ++v) {
    const Word* row = g.row(v);
    for (int w = 0; w < W; ++w) {
      Word x = ~row[w];
      if (w == W - 1 && n_ % kBits != 0) x &= (Word{1} << (n_ % kBits)) - 1;
      if (w == v / kBits) x &= ~(Word{1} << (v % kBits));
      for (; x; x &= x - 1) nbr_.push_back(w * kBits + lowest_bit(x));
    }
    off_[static_cast<std::size_t>(v) + 1] = static_cast<int>(nbr_.size());
    deg_[static_cast<std::size_t>(v)] = off_[static_cast<std::size_t>(v) + 1] - off_[v];
    if ((v & 255) == 255) throw_if_past(budget_.deadline);
  }
  // A greedy maximal matching to start from: Hopcroft-Karp then needs a few phases, not ~sqrt(n).
  for (int u = 0; u < n_; ++u) {
    for (int k = off_[u]; k < off_[u + 1]; ++k) {
      const int v = nbr_[static_cast<std::size_t>(k)];
      if (mate_r_[static_cast<std::size_t>(v)] < 0) {
        mate_l_[static_cast<std::size_t>(u)] = v;
        mate_r_[static_cast<std::size_t>(v)] = u;
        break;
      }
    }
  }
}

namespace {

// Kuhn's augmenting paths in H's double cover, from left vertex u, over right vertices not yet
// visited in this phase; rows of g complemented word by word. H is g's complement on the vertices
// of `valid` (a bitset of W words: g's rows are read no further), listed in `members`; the
// matching lives in `state` and is kept for a later call on an overlapping set.
class DoubleCoverMatching {
 public:
  DoubleCoverMatching(const BitGraph& g, const std::vector<int>& members, const Word* valid,
                      int W, LpMatching& state)
      : g_(g), members_(members), valid_(valid), W_(W), s_(state) {
    const std::size_t n = static_cast<std::size_t>(g.size());
    if (s_.mate_l.size() != n) {
      s_.mate_l.assign(n, -1);
      s_.mate_r.assign(n, -1);
    }
    const std::size_t words = static_cast<std::size_t>(W_);
    if (s_.visited.size() < words) s_.visited.resize(words);
    // What is left of the last matching among the members: pairs whose ends both stay (an edge of
    // H then still), each pair seen from both ends.
    for (int u : members_) {
      int& v = s_.mate_l[static_cast<std::size_t>(u)];
      if (v >= 0 && !(in(v) && s_.mate_r[static_cast<std::size_t>(v)] == u)) v = -1;
    }
    for (int v : members_) {
      int& u = s_.mate_r[static_cast<std::size_t>(v)];
      if (u >= 0 && !(in(u) && s_.mate_l[static_cast<std::size_t>(u)] == v)) u = -1;
      if (u >= 0) ++size_;
    }
  }

  // Greedy, then phases of augmenting paths until none is left or the matching reaches `goal`.
  int grow(int goal) {
    std::vector<Word> free_r(valid_, valid_ + W_);
    for (int v : members_) {
      if (s_.mate_r[static_cast<std::size_t>(v)] >= 0) clear(free_r.data(), v);
    }
    int first = 0;  // free_r's words before it are empty
    for (std::size_t k = 0; k < members_.size() && size_ < goal; ++k) {
      const int u = members_[k];
      if (s_.mate_l[static_cast<std::size_t>(u)] >= 0) continue;
      while (first < W_ && free_r[static_cast<std::size_t>(first)] == 0) ++first;
      for (int w = first; w < W_; ++w) {
        const Word x = h_word(u, w) & free_r[static_cast<std::size_t>(w)];
        if (x == 0) continue;
        const int v = w * kBits + lowest_bit(x);
        match(u, v);
        ++size_;
        clear(free_r.data(), v);
        break;
      }
    }
    for (bool grew = true; grew && size_ < goal;) {
      grew = false;
      std::fill(s_.visited.begin(), s_.visited.begin() + W_, 0);
      for (std::size_t k = 0; k < members_.size() && size_ < goal; ++k) {
        const int u = members_[k];
        if (s_.mate_l[static_cast<std::size_t>(u)] < 0 && augment(u)) {
          ++size_;
          grew = true;
        }
      }
    }
    return size_;
  }

 private:
  // A kept mate may lie beyond the `W_` words the caller vouches for: not a member then.
  bool in(int v) const { return v / kBits < W_ && ((valid_[v / kBits] >> (v % kBits)) & 1); }
  static void clear(Word* bits, int v) { bits[v / kBits] &= ~(Word{1} << (v % kBits)); }
  Word h_word(int u, int w) const {
    Word x = ~g_.row(u)[w] & valid_[w];
    if (w == u / kBits) x &= ~(Word{1} << (u % kBits));
    return x;
  }
  void match(int u, int v) {
    s_.mate_l[static_cast<std::size_t>(u)] = v;
    s_.mate_r[static_cast<std::size_t>(v)] = u;
  }
  // Kuhn's depth-first search from the unmatched u_L, on an explicit stack (a path can hold every
  // member: tens of thousands of calls deep on large near-cliques, past a thread's stack). Each
  // level scans its left vertex's unvisited right neighbours in order from the word it stopped at;
  // via_[i] is the right vertex level i went through to reach level i + 1.
  bool augment(int root) {
    Word* visited = s_.visited.data();
    path_.assign(1, root);
    at_.assign(1, 0);
    via_.clear();
    while (!path_.empty()) {
      const int u = path_.back();
      int& w = at_.back();
      int v = -1;
      for (; w < W_; ++w) {
        if (const Word x = h_word(u, w) & ~visited[w]) {
          v = w * kBits + lowest_bit(x);
          break;
        }
      }
      if (v < 0) {  // no way on from u: back to the level before, which goes on scanning
        path_.pop_back();
        at_.pop_back();
        if (!via_.empty()) via_.pop_back();
        continue;
      }
      visited[w] |= Word{1} << (v % kBits);
      via_.push_back(v);
      const int m = s_.mate_r[static_cast<std::size_t>(v)];
      if (m < 0) {  // v is free: every level takes the right vertex it went through
        for (std::size_t i = 0; i < path_.size(); ++i) match(path_[i], via_[i]);
        return true;
      }
      path_.push_back(m);
      at_.push_back(0);
    }
    return false;
  }

  const BitGraph& g_;
  const std::vector<int>& members_;
  const Word* valid_;
  const int W_;
  LpMatching& s_;
  int size_ = 0;
  std::vector<int> path_, at_, via_;  // augment()'s stack
};

}  // namespace

bool lp_rules_out(const BitGraph& g, const std::vector<int>& members, const Word* valid, int words,
                  int target, LpMatching& state) {
  // omega <= n - ceil(|M| / 2) <= target once |M| >= 2 (n - target) - 1.
  const int n = static_cast<int>(members.size());
  if (n <= target) return true;
  const int goal = 2 * (n - target) - 1;
  if (goal > n) return false;  // a matching of the double cover has at most n edges
  return DoubleCoverMatching(g, members, valid, words, state).grow(goal) >= goal;
}

bool lp_rules_out(const BitGraph& g, int target) {
  const int n = g.size();
  if (n <= target) return true;
  if (2 * (n - target) - 1 > n) return false;
  std::vector<int> all(static_cast<std::size_t>(n));
  for (int v = 0; v < n; ++v) all[static_cast<std::size_t>(v)] = v;
  std::vector<Word> valid(static_cast<std::size_t>(g.words()), ~Word{0});
  if (n % kBits != 0) valid.back() = (Word{1} << (n % kBits)) - 1;
  LpMatching state;
  return lp_rules_out(g, all, valid.data(), g.words(), target, state);
}

namespace {

std::vector<int> near_clique_cover(const BitGraph& g, const Word* P, int target,
                                   SearchBudget& budget, NearCliqueScratch& scratch) {
  std::vector<Word>& mask = scratch.mask;
  if (mask.empty()) mask.assign(static_cast<std::size_t>(g.words()), 0);
  std::vector<int> members;
  for_each_bit(P, g.words(), [&](int v) { members.push_back(v); });
  // The LP bound alone, on the rows, ends most such nodes before the cover search lists the
  // complement (k00_199_198 0.3 k3: 11.6 -> 2.7 s; BENCHMARK.md, section 51): first on P as it
  // is, from the last node's matching, then, when that fails, on the core a better clique needs
  // (target + 1 of these vertices), where it can only be tighter.
  if (lp_rules_out(g, members, P, g.words(), target, scratch.matching)) return {};
  const std::size_t before = members.size();
  const BitGraph sub = core_subgraph(g, members, target, mask, budget.deadline);
  if (sub.size() <= target || (members.size() < before && lp_rules_out(sub, target))) return {};
  CoverSearch cover(sub, target, budget);
  cover.run();
  std::vector<int> found;
  for (int k : cover.best()) found.push_back(members[static_cast<std::size_t>(k)]);
  return found;
}

}  // namespace

void hand_off_near_clique(const BitGraph& g, const Word* P, const std::vector<int>& clique,
                          std::vector<int>& best, int& best_size, SearchBudget& budget,
                          NearCliqueScratch& scratch) {
  const int size = static_cast<int>(clique.size());
  // Past the deadline the peel and the cover search's set-up throw DeadlinePassed: the search
  // stops here with the best it has (a caller's catch would keep only its own incumbent).
  try {
    const std::vector<int> found = near_clique_cover(g, P, best_size - size, budget, scratch);
    if (!found.empty() && size + static_cast<int>(found.size()) > best_size) {
      best = clique;
      best.insert(best.end(), found.begin(), found.end());
      best_size = static_cast<int>(best.size());
    }
  } catch (const DeadlinePassed&) {
    budget.stopped = true;
  }
}

void CoverSearch::run() { node(0); }

int CoverSearch::needed() const { return best_size_ - static_cast<int>(set_.size()) + 1; }

bool CoverSearch::lp_can_help() const { return alive_count_ < 2 * needed() + kLpMargin; }

void CoverSearch::set_left(int u, int v) {
  log_.push_back({u, mate_l_[static_cast<std::size_t>(u)]});
  mate_l_[static_cast<std::size_t>(u)] = v;
}

void CoverSearch::set_right(int v, int u) {
  log_.push_back({~v, mate_r_[static_cast<std::size_t>(v)]});
  mate_r_[static_cast<std::size_t>(v)] = u;
}

void CoverSearch::undo_matching(std::size_t log_size) {
  while (log_.size() > log_size) {
    const auto [at, old] = log_.back();
    log_.pop_back();
    if (at >= 0) {
      mate_l_[static_cast<std::size_t>(at)] = old;
    } else {
      mate_r_[static_cast<std::size_t>(~at)] = old;
    }
  }
}

void CoverSearch::swap_entries(int a, int b) {
  std::swap(nbr_[static_cast<std::size_t>(a)], nbr_[static_cast<std::size_t>(b)]);
  std::swap(twin_[static_cast<std::size_t>(a)], twin_[static_cast<std::size_t>(b)]);
  twin_[static_cast<std::size_t>(twin_[static_cast<std::size_t>(a)])] = a;
  twin_[static_cast<std::size_t>(twin_[static_cast<std::size_t>(b)])] = b;
}

void CoverSearch::go_live() {
  // twin_[k]: where the edge of entry k sits in its other end's list (the lists still ascend, so
  // each list's entries are met in order as u ascends).
  twin_.resize(nbr_.size());
  std::vector<int> cursor(off_.begin(), off_.end() - 1);
  for (int u = 0; u < n_; ++u) {
    for (int k = off_[u]; k < off_[u + 1]; ++k) {
      const int v = nbr_[static_cast<std::size_t>(k)];
      twin_[static_cast<std::size_t>(k)] = cursor[static_cast<std::size_t>(v)]++;
    }
  }
  for (int u = 0; u < n_; ++u) {
    if (alive_[static_cast<std::size_t>(u)]) live_first(u);
  }
  live_ = true;
  live_from_ = trail_.size();
}

void CoverSearch::live_first(int u) {
  int i = off_[u], j = off_[u + 1] - 1;
  while (i <= j) {
    if (alive_[static_cast<std::size_t>(nbr_[static_cast<std::size_t>(i)])]) {
      ++i;
    } else {
      swap_entries(i, j--);
    }
  }
}

void CoverSearch::remove(int v) {
  alive_[static_cast<std::size_t>(v)] = 0;
  --alive_count_;
  trail_.push_back(v);
  if (live_) {
    // v's entry in each live neighbour's list moves to just past that list's live part.
    for (int k = off_[v], end = scan_end(v); k < end; ++k) {
      const int u = nbr_[static_cast<std::size_t>(k)];
      const int last = --deg_[static_cast<std::size_t>(u)] + off_[u];
      swap_entries(twin_[static_cast<std::size_t>(k)], last);
    }
  } else {
    for (int k = off_[v]; k < off_[v + 1]; ++k) {
      const int u = nbr_[static_cast<std::size_t>(k)];
      if (alive_[static_cast<std::size_t>(u)]) --deg_[static_cast<std::size_t>(u)];
    }
  }
  if (const int r = mate_l_[static_cast<std::size_t>(v)]; r >= 0) {
    set_right(r, -1);
    set_left(v, -1);
  }
  if (const int l = mate_r_[static_cast<std::size_t>(v)]; l >= 0) {
    set_left(l, -1);
    set_right(v, -1);
  }
}

void CoverSearch::take(int v) {
  set_.push_back(v);
  if (live_) {
    // Each removal takes the last live entry of v's list out of its live part.
    while (deg_[static_cast<std::size_t>(v)] > 0) {
      remove(nbr_[static_cast<std::size_t>(scan_end(v) - 1)]);
    }
  } else {
    for (int k = off_[v]; k < off_[v + 1]; ++k) {
      const int u = nbr_[static_cast<std::size_t>(k)];
      if (alive_[static_cast<std::size_t>(u)]) remove(u);
    }
  }
  remove(v);
}

void CoverSearch::restore(std::size_t trail_size) {
  // In reverse order, so that every degree comes back to what it was.
  while (trail_.size() > trail_size) {
    const int v = trail_.back();
    trail_.pop_back();
    alive_[static_cast<std::size_t>(v)] = 1;
    ++alive_count_;
    if (live_ && trail_.size() >= live_from_) {
      // v's live part was frozen when it left and holds exactly the neighbours live again now;
      // v's entry lies just past each one's live part (later removals' entries came back first).
      for (int k = off_[v], end = scan_end(v); k < end; ++k) {
        ++deg_[static_cast<std::size_t>(nbr_[static_cast<std::size_t>(k)])];
      }
    } else if (live_) {
      // Removed before go_live(): v's entry goes back into each live neighbour's live part, and
      // v's own list is split as go_live() split the others.
      live_from_ = trail_.size();
      for (int k = off_[v]; k < off_[v + 1]; ++k) {
        const int u = nbr_[static_cast<std::size_t>(k)];
        if (!alive_[static_cast<std::size_t>(u)]) continue;
        const int first_out = off_[u] + deg_[static_cast<std::size_t>(u)]++;
        swap_entries(twin_[static_cast<std::size_t>(k)], first_out);
      }
      live_first(v);
    } else {
      for (int k = off_[v]; k < off_[v + 1]; ++k) {
        const int u = nbr_[static_cast<std::size_t>(k)];
        if (alive_[static_cast<std::size_t>(u)]) ++deg_[static_cast<std::size_t>(u)];
      }
    }
  }
}

// Hopcroft-Karp layers from the unmatched u_L, up to the first layer that meets an unmatched v_R.
// When none is met the search ran to the end: dist_ >= 0 then marks exactly the u_L reachable by
// alternating paths (what the LP reduction reads).
bool CoverSearch::bfs() {
  queue_.clear();
  for (int u = 0; u < n_; ++u) {
    dist_[static_cast<std::size_t>(u)] = -1;
    if (alive_[static_cast<std::size_t>(u)] && mate_l_[static_cast<std::size_t>(u)] < 0) {
      dist_[static_cast<std::size_t>(u)] = 0;
      queue_.push_back(u);
    }
  }
  bool found = false;
  int found_at = -1;  // the layer where an unmatched v_R was met: layers past it are not needed
  for (std::size_t head = 0; head < queue_.size(); ++head) {
    const int u = queue_[head];
    if (found && dist_[static_cast<std::size_t>(u)] > found_at) break;
    for (int k = off_[u], end = scan_end(u); k < end; ++k) {
      const int v = nbr_[static_cast<std::size_t>(k)];
      if (!alive_[static_cast<std::size_t>(v)]) continue;
      const int w = mate_r_[static_cast<std::size_t>(v)];
      if (w < 0) {
        if (!found) found_at = dist_[static_cast<std::size_t>(u)];
        found = true;
      } else if (dist_[static_cast<std::size_t>(w)] < 0) {
        dist_[static_cast<std::size_t>(w)] = dist_[static_cast<std::size_t>(u)] + 1;
        queue_.push_back(w);
      }
    }
  }
  return found;
}

// An augmenting path from the unmatched u_L along the layers, iteratively (paths can be as long
// as the graph).
bool CoverSearch::dfs(int root) {
  stack_.assign(1, root);
  while (!stack_.empty()) {
    const int x = stack_.back();
    int& at = iter_[static_cast<std::size_t>(x)];
    if (at == scan_end(x)) {
      dist_[static_cast<std::size_t>(x)] = -2;  // a dead end for the rest of this phase
      stack_.pop_back();
      if (!stack_.empty()) ++iter_[static_cast<std::size_t>(stack_.back())];
      continue;
    }
    const int v = nbr_[static_cast<std::size_t>(at)];
    if (!alive_[static_cast<std::size_t>(v)]) {
      ++at;
      continue;
    }
    const int w = mate_r_[static_cast<std::size_t>(v)];
    if (w < 0) {  // augment: each vertex of the stack takes the edge it stands on
      for (const int s : stack_) {
        const int t = nbr_[static_cast<std::size_t>(iter_[static_cast<std::size_t>(s)])];
        set_left(s, t);
        set_right(t, s);
      }
      return true;
    }
    if (dist_[static_cast<std::size_t>(w)] == dist_[static_cast<std::size_t>(x)] + 1) {
      stack_.push_back(w);
    } else {
      ++at;
    }
  }
  return false;
}

void CoverSearch::augment() {
  while (bfs()) {
    for (int u = 0; u < n_; ++u) iter_[static_cast<std::size_t>(u)] = off_[u];
    for (int u = 0; u < n_; ++u) {
      if (alive_[static_cast<std::size_t>(u)] && mate_l_[static_cast<std::size_t>(u)] < 0) dfs(u);
    }
  }
}

bool CoverSearch::reduce_degrees() {
  bool changed = false;
  for (int v = 0; v < n_; ++v) {
    if (!alive_[static_cast<std::size_t>(v)]) continue;
    const int d = deg_[static_cast<std::size_t>(v)];
    if (d <= 1) {
      take(v);  // degree 0: in the set; degree 1: in the set, its neighbour in the cover
      changed = true;
    } else if (alive_count_ - d < needed()) {
      remove(v);  // with v, at most alive - d more: no set larger than the best (the k-core rule)
      changed = true;
    }
  }
  return changed;
}

bool CoverSearch::reduce_lp() {
  augment();
  for (int v = 0; v < n_; ++v) z_r_[static_cast<std::size_t>(v)] = 0;
  for (int u = 0; u < n_; ++u) {
    if (!alive_[static_cast<std::size_t>(u)] || dist_[static_cast<std::size_t>(u)] < 0) continue;
    for (int k = off_[u], end = scan_end(u); k < end; ++k) {
      const int v = nbr_[static_cast<std::size_t>(k)];
      if (alive_[static_cast<std::size_t>(v)]) z_r_[static_cast<std::size_t>(v)] = 1;
    }
  }
  // x_v = 1: into the cover; x_v = 0: their only neighbours are x = 1 vertices, so into the set.
  ones_.clear();
  zeros_.clear();
  for (int v = 0; v < n_; ++v) {
    if (!alive_[static_cast<std::size_t>(v)]) continue;
    const bool in_z_left = dist_[static_cast<std::size_t>(v)] >= 0;
    const bool in_z_right = z_r_[static_cast<std::size_t>(v)] != 0;
    if (in_z_left && !in_z_right) zeros_.push_back(v);
    if (!in_z_left && in_z_right) ones_.push_back(v);
  }
  if (ones_.empty() && zeros_.empty()) return false;
  for (const int v : ones_) remove(v);
  for (const int v : zeros_) {
    set_.push_back(v);
    remove(v);
  }
  return true;
}

bool CoverSearch::reduce() {
  for (;;) {
    const bool degrees = reduce_degrees();
    if (!lp_can_help()) return false;
    if (!reduce_lp() && !degrees) return true;
  }
}

// The matching is maximum here (reduce() ended on an LP pass that removed nothing).
int CoverSearch::cover_lower_bound() {
  for (int v = 0; v < n_; ++v) seen_[static_cast<std::size_t>(v)] = 0;
  int bound = 0;
  for (int u = 0; u < n_; ++u) {  // paths: start where no matched edge comes in
    if (!alive_[static_cast<std::size_t>(u)] || mate_r_[static_cast<std::size_t>(u)] >= 0) continue;
    int k = 0;
    for (int x = u; x >= 0; x = mate_l_[static_cast<std::size_t>(x)]) {
      seen_[static_cast<std::size_t>(x)] = 1;
      ++k;
    }
    bound += k / 2;
  }
  for (int u = 0; u < n_; ++u) {  // what is left lies on cycles
    if (!alive_[static_cast<std::size_t>(u)] || seen_[static_cast<std::size_t>(u)]) continue;
    cycle_.clear();
    int x = u;
    do {
      seen_[static_cast<std::size_t>(x)] = 1;
      cycle_.push_back(x);
      x = mate_l_[static_cast<std::size_t>(x)];
    } while (x != u);
    const int len = static_cast<int>(cycle_.size());
    bool clique = len >= 4 && len <= kMaxCliqueCycle;
    for (int a = 0; clique && a < len; ++a) {
      for (int b = a + 1; clique && b < len; ++b) {
        clique =
            h_adjacent(cycle_[static_cast<std::size_t>(a)], cycle_[static_cast<std::size_t>(b)]);
      }
    }
    bound += clique ? len - 1 : (len + 1) / 2;
  }
  return bound;
}

// The subtree on the vertices left, packed into a graph of their own: the matching passes then
// touch only live adjacency (most of a deep node's lists are vertices removed above it).
void CoverSearch::search_packed() {
  std::vector<int> vertices, index(static_cast<std::size_t>(n_), -1);
  for (int v = 0; v < n_; ++v) {
    if (alive_[static_cast<std::size_t>(v)]) {
      index[static_cast<std::size_t>(v)] = static_cast<int>(vertices.size());
      vertices.push_back(v);
    }
  }
  const BitGraph packed = permuted(g_, vertices, budget_.deadline);
  CoverSearch child(packed, best_size_ - static_cast<int>(set_.size()), budget_);
  std::fill(child.mate_l_.begin(), child.mate_l_.end(), -1);
  std::fill(child.mate_r_.begin(), child.mate_r_.end(), -1);
  for (std::size_t k = 0; k < vertices.size(); ++k) {  // start from this node's matching
    const int m = mate_l_[static_cast<std::size_t>(vertices[k])];
    if (m < 0) continue;
    const int j = index[static_cast<std::size_t>(m)];
    child.mate_l_[k] = j;
    child.mate_r_[static_cast<std::size_t>(j)] = static_cast<int>(k);
  }
  child.run();
  if (child.best().empty()) return;
  best_ = set_;
  for (const int k : child.best()) best_.push_back(vertices[static_cast<std::size_t>(k)]);
  best_size_ = static_cast<int>(best_.size());
}

// The independent sets of a disconnected graph are unions of one per component: the smaller
// components are solved exactly first, then the largest needs only what a better set still lacks
// (the component rule of Akiba & Iwata). The clique side of this: G is the join of the parts.
bool CoverSearch::split_components() {
  std::vector<std::vector<int>> parts;
  std::vector<char> labelled(static_cast<std::size_t>(n_), 0);
  for (int s = 0; s < n_; ++s) {
    if (!alive_[static_cast<std::size_t>(s)] || labelled[static_cast<std::size_t>(s)]) continue;
    std::vector<int> part{s};
    labelled[static_cast<std::size_t>(s)] = 1;
    for (std::size_t head = 0; head < part.size(); ++head) {
      const int u = part[head];
      for (int k = off_[u], end = scan_end(u); k < end; ++k) {
        const int v = nbr_[static_cast<std::size_t>(k)];
        if (alive_[static_cast<std::size_t>(v)] && !labelled[static_cast<std::size_t>(v)]) {
          labelled[static_cast<std::size_t>(v)] = 1;
          part.push_back(v);
        }
      }
    }
    if (static_cast<int>(part.size()) == alive_count_) return false;  // connected
    std::sort(part.begin(), part.end());
    parts.push_back(std::move(part));
  }
  std::stable_sort(parts.begin(), parts.end(),
                   [](const auto& a, const auto& b) { return a.size() < b.size(); });
  std::vector<int> chosen = set_;
  auto solve = [&](const std::vector<int>& part, int incumbent) {
    const BitGraph packed = permuted(g_, part, budget_.deadline);
    CoverSearch child(packed, incumbent, budget_);
    child.run();
    for (const int k : child.best()) chosen.push_back(part[static_cast<std::size_t>(k)]);
    return !child.best().empty();
  };
  for (std::size_t i = 0; i + 1 < parts.size(); ++i) {
    solve(parts[i], 0);  // its maximum independent set
    if (budget_.stopped) return true;
  }
  const int lacking = best_size_ - static_cast<int>(chosen.size());
  if (solve(parts.back(), std::max(0, lacking)) && static_cast<int>(chosen.size()) > best_size_) {
    best_ = std::move(chosen);
    best_size_ = static_cast<int>(best_.size());
  }
  return true;
}

int CoverSearch::branch_vertex() const {
  int pick = -1;
  for (int v = 0; v < n_; ++v) {
    if (alive_[static_cast<std::size_t>(v)] &&
        (pick < 0 || deg_[static_cast<std::size_t>(v)] > deg_[static_cast<std::size_t>(pick)])) {
      pick = v;
    }
  }
  return pick;
}

void CoverSearch::node(int depth) {
  // A node costs a matching pass over H (up to milliseconds): the clock is read at every one.
  if (!budget_.spend() || SteadyClock::now() >= budget_.deadline) {
    budget_.stopped = true;
    return;
  }
  const std::size_t trail_mark = trail_.size(), set_mark = set_.size();
  const bool matched = reduce();
  const int upper =
      static_cast<int>(set_.size()) + alive_count_ - (matched ? cover_lower_bound() : 0);
  if (depth == 0) root_upper_ = std::max(best_size_, upper);
  if (upper > best_size_) {
    if (alive_count_ == 0) {
      best_ = set_;
      best_size_ = static_cast<int>(set_.size());
    } else if (split_components()) {
      // each component solved on its own
    } else if (depth > 0 && alive_count_ >= kMinPacked && alive_count_ * kPackRatio <= n_) {
      search_packed();
    } else {
      // Past kLiveAfter nodes, removals keep each list's live part first (go_live()).
      if (!live_ && ++branches_ > kLiveAfter) go_live();
      const int v = branch_vertex();
      const std::size_t mark = trail_.size(), log_mark = log_.size(), branch_set = set_.size();
      remove(v);  // v in the cover
      node(depth + 1);
      restore(mark);
      undo_matching(log_mark);
      if (!budget_.stopped) {
        take(v);  // v in the set
        node(depth + 1);
        restore(mark);
        undo_matching(log_mark);
        set_.resize(branch_set);
      }
    }
  }
  // run() is called once and the lists are not read after the root: its removals stay.
  if (depth > 0) restore(trail_mark);
  set_.resize(set_mark);
}

}  // namespace verifybench::detail
