#pragma once
// Maximum clique of a near-clique as the complement of a minimum vertex cover (internal to
// cliques/). A clique of G is an independent set of its complement H, so
//   omega(G) = n - tau(H)        (tau: the size of a minimum vertex cover)
// and when G is dense, H is sparse: branch and reduce on H (Akiba & Iwata 2016) proves graphs
// whose colouring bounds are hopeless (correspondence graphs with 25-70% inliers: cliques of
// 500-2500 among 1000-4000 candidates, a greedy colouring 3-5% above omega).
//
// Bound: the LP relaxation of vertex cover is half-integral and solved by a maximum matching M in
// the bipartite double cover of H (u_L -- v_R for every edge uv). Read as a partial permutation
// u -> M(u_L), M splits the vertices into disjoint paths and cycles of H; a path of k vertices
// needs floor(k / 2) of them in any cover, a cycle of length k needs ceil(k / 2), or k - 1 when its
// vertices are a clique of H. Their sum is at least the LP bound (the cycle-cover bound of Akiba
// & Iwata).
// Reductions, until none applies: a vertex of degree 0 joins the independent set; one of degree 1
// joins it and its neighbour joins the cover; a vertex with fewer non-neighbours left than a better
// set needs joins the cover (the k-core rule of clique searches); the LP reduction of Nemhauser &
// Trotter (1975): with Z the vertices reachable from unmatched u_L by alternating paths, x_v = 0
// when v_L in Z and v_R not in Z (v joins the set), x_v = 1 when v_L not in Z and v_R in Z (v joins
// the cover); some minimum cover agrees with any optimal LP solution on its integral part.
// Components: a disconnected H is solved one component at a time, the largest last.
// Branching: the vertex of highest degree in H, first into the cover, then into the set (all its
// neighbours into the cover). The matching is kept from node to node and only re-augmented.
#include <vector>

#include "cliques/detail/bbmc.hpp"

namespace verifybench::detail {

/// Whether the LP bound of the complement H alone shows that `g` has no clique larger than
/// `target`: a maximum matching M of H's bipartite double cover gives tau(H) >= ceil(|M| / 2), so
/// omega(g) <= n - ceil(|M| / 2). Bit-parallel on g's rows (H is never listed): O(n x words) a
/// phase of augmenting paths, against the lists a CoverSearch builds first (n^2 / 2 entries at
/// density 0.5). Stops as soon as the matching is large enough.
bool lp_rules_out(const BitGraph& g, int target);

/// lp_rules_out on g's subgraph on `members` (ascending ids), given also as the bitset `valid` of
/// g's first `words` words (no member beyond them, the rest of the bitset unread), without
/// building it; the matching starts from what `state` holds and is left there.
bool lp_rules_out(const BitGraph& g, const std::vector<int>& members, const Word* valid, int words,
                  int target, LpMatching& state);

/// A branch-and-bound search's hand-off of a near-clique node (BBMCX's, bbmcx-sat's): a clique of P
/// larger than best_size - |clique|, in ids of g: the LP bound (lp_rules_out, from the scratch's
/// matching, kept for the next node), the peel to the core such a clique needs, the LP bound
/// there, then the cover search; when found, `clique` plus it becomes `best`. Past the deadline it
/// stops the search (budget.stopped) with the best it has.
void hand_off_near_clique(const BitGraph& g, const Word* P, const std::vector<int>& clique,
                          std::vector<int>& best, int& best_size, SearchBudget& budget,
                          NearCliqueScratch& scratch);

class CoverSearch {
 public:
  /// `g`: the graph (G, not its complement), vertex order irrelevant; `incumbent`: the size to
  /// beat.
  CoverSearch(const BitGraph& g, int incumbent, SearchBudget& budget);

  /// Searches (once per object); best() is empty unless a clique larger than the incumbent was
  /// found.
  void run();
  const std::vector<int>& best() const { return best_; }  ///< ids of g
  /// An upper bound on the clique number of g from the reduced root (valid once run() returned,
  /// whether or not the search finished); at least the incumbent.
  int upper_bound() const { return root_upper_; }

 private:
  void node(int depth);
  bool reduce();  // true when it ended with a maximum matching (then the bound uses it)
  bool reduce_degrees();
  int needed() const;  // the size an independent set of what is left needs to improve
  bool lp_can_help() const;
  bool reduce_lp();
  void augment();
  bool bfs();
  bool dfs(int u);
  int cover_lower_bound();
  int branch_vertex() const;
  void search_packed();
  bool split_components();  // false when what is left is connected

  void set_left(int u, int v);   // mate_l_[u] = v, logged
  void set_right(int v, int u);  // mate_r_[v] = u, logged
  void undo_matching(std::size_t log_size);
  void remove(int v);  // v leaves the graph (into the cover, or into the set by take())
  void take(int v);    // v into the independent set, its neighbours into the cover
  void restore(std::size_t trail_size);
  bool h_adjacent(int u, int v) const { return u != v && !g_.adjacent(u, v); }
  // Where a scan of v's list ends: once live_, off_[v] .. scan_end(v) lists exactly v's live
  // neighbours (while v is live; the part of a vertex removed after go_live() is frozen with those
  // live when it left; one removed before is split when it comes back), before that the whole
  // list.
  int scan_end(int v) const {
    const auto k = static_cast<std::size_t>(v);
    return live_ ? off_[k] + deg_[k] : off_[k + 1];
  }
  // The lists' live parts, once a search has branched more than kLiveAfter times (a short
  // search would pay the set-up; a deep node's lists are mostly removed vertices).
  void go_live();
  void live_first(int u);           // u's list split: its live neighbours first
  void swap_entries(int a, int b);  // two entries of one list, with their twins

  const BitGraph& g_;
  const int n_;
  int best_size_;
  SearchBudget& budget_;
  int root_upper_;
  // H as adjacency lists (CSR); once live_, each with its live neighbours first, and twin_[k] is
  // the position of entry k's edge in the other end's list (what a removal swaps in O(1)).
  std::vector<int> off_, nbr_, twin_;
  bool live_ = false;
  std::size_t live_from_ = 0;  // trail_ entries from here on left after go_live()
  int branches_ = 0;
  std::vector<char> alive_;
  std::vector<int> deg_;    // degree among alive vertices (frozen while a vertex is removed)
  std::vector<int> trail_;  // removed vertices, in order
  std::vector<int> set_;    // the independent set built so far (a clique of g)
  std::vector<int> best_;
  int alive_count_;
  // Matching in the double cover: mate_l_[u] = v when u_L -- v_R is matched, mate_r_[v] = u.
  std::vector<int> mate_l_, mate_r_;
  struct Change {
    int at;  // u for mate_l_[u], ~v for mate_r_[v]
    int old;
  };
  std::vector<Change> log_;  // matching changes, undone on backtracking
  std::vector<int> dist_, iter_, queue_, stack_, ones_, zeros_, cycle_;
  std::vector<char> z_r_, seen_;
};

}  // namespace verifybench::detail
