#pragma once
// Bitset branch and bound with an incremental MaxSAT bound over the colour classes (bbmcx-sat).
// Internal to cliques/. The bound is the one of Li & Quan's MaxCLQ / IncMaxCLQ (AAAI 2010,
// "An efficient branch-and-bound algorithm based on MaxSAT for the maximum clique problem";
// "Combining MaxSAT reasoning and incremental upper bound for the maximum clique problem",
// ICTAI 2010) as MoMC (Li, Jiang & Manya, C&OR 2017) and LMC (Jiang, Li & Manya, ECAI 2016)
// apply it to the branching set, written here on BBMC's bitsets:
//
// A node's candidates P are greedily coloured. With incumbent b and clique C, only classes past
// r = b - |C| matter: the vertices there form the branching set B, the rest A (classes C_1..C_r).
// Read each class as a soft clause "some vertex of C_k is in the clique" and each non-edge as a
// hard clause; then a clique of A u {v} takes at most (number of classes) - (number of disjoint
// inconsistent subsets of classes) vertices. For each v in B (colour order) we add the singleton
// class {v} and run unit propagation: v true removes its non-neighbours from every class, a class
// left with one vertex becomes a unit and propagates in turn, a class left empty is a conflict.
// The classes the conflict depends on (found by walking back the units that removed vertices,
// the standard conflict analysis) with {v} are an inconsistent subset: v moves from B into A and
// v is never branched on. Those classes are then relaxed (SatOptions::relax, as LMC, MoMC and
// CliSAT do): each takes one new literal they share, which satisfies at most one of them (a
// unit whose last member is the literal sets it for itself and takes it from the others), the
// group's refuted vertices become a class with it too, and all of them stay in the later tests
// but take no vertex in. Any clique misses a class of the subset, which the literal pays for, so
// the relaxed classes bound A u {refuted} by the same r: the bound of the relaxed formula plus
// one per subset (MoMC's and LMC's incremental MaxSAT reasoning). Without relaxation the classes
// are frozen instead (later tests and re-numbering skip them, which keeps the subsets disjoint).
// The vertices of one colour class of B are pairwise non-adjacent, so a clique holds at most one
// of them: they share their subsets, each testing against the classes its group's earlier members
// froze too, and the classes freeze (or are relaxed) for good when the next colour begins (a
// clique with one of them misses a class of its subset; the union of the group's subsets with the
// group loses one vertex either way). A shared class takes no vertex in, and one with no
// neighbour of v left is a subset with v by itself. On dense graphs 14-21% fewer nodes
// (BENCHMARK.md, section 47). Before the test, v is re-numbered into a low class when it can be
// (Tomita's Re-NUMBER, BBMCR), which keeps every class (SatOptions::renumber). A vertex left in
// B at colour c keeps the bound min(c, r + its rank in B): the low classes bound A by r, and B's
// first vertices by their colours or their count.
//
// Where unit propagation alone finds no conflict, each low class of two vertices left can be
// tested by failed literals (IncMaxCLQ, MoMC; SatOptions::failed_literals): when every one of its
// vertices, set true on top of the propagation, leads to a conflict, the class with the union of
// their reasons is inconsistent.
//
// Cost: a test keeps the members left as a bitset and a count per class; setting u true clears
// u's non-neighbours a word at a time and walks only those (a few bits on dense graphs) instead
// of intersecting every class with u's row: on MANN_a27 (density 0.99) 5x cheaper (316 -> 62
// ms; section 42).
#include <vector>

#include "cliques/detail/bbmc.hpp"
#include "cliques/detail/local_search.hpp"

namespace verifybench::detail {

/// What the test tries besides unit propagation. Both pay on the sparse neighbourhoods of
/// correspondence graphs (the corpus's k00_198_94 0.5 k10 through the decomposition: 157,000
/// nodes and 8.7 s with them, 740,000 and 24 s without) and cost more than they save on dense
/// graphs (p_hat300-3's decomposition 140 -> 117 ms without them, C125.9 8.7 -> 6.8 ms, MANN_a27
/// 57 -> 43 ms; BENCHMARK.md, sections 45 and 46).
struct SatOptions {
  bool renumber = true;         ///< Re-NUMBER v before the test
  bool failed_literals = true;  ///< probe the classes of two vertices left where propagation stops
  /// Relax an inconsistent subset instead of freezing it (LMC, MoMC, CliSAT): each of its classes
  /// takes one shared relaxation literal (at most one class of the subset is satisfied by it) and
  /// stays in the later tests; the group's refuted vertices become a class of their own.
  /// Pays on dense graphs (auto's path from density 0.85, with used-first units: MANN_a27 40 -> 21
  /// ms, G(200, 0.9) 1.86M -> 0.92M nodes and 0.82x the time) and without used-first costs 9-44%
  /// in the decomposition's neighbourhoods at density 0.6-0.75
  /// (brock200_4, sanr200_0.7, p_hat500-1: 10-30% fewer nodes, each test dearer; BENCHMARK.md,
  /// section 56). With Re-NUMBER and failed literals it pays in the neighbourhoods of auto's
  /// hand-off of long sparse searches below density 0.2, whose cliques run to hundreds
  /// (balm_realworld's b148_51 FPFH 0.5 k3 4.1 -> 1.9 s; section 63).
  bool relax = false;
};

class SatBranchAndBound {
 public:
  SatBranchAndBound(const BitGraph& g, int incumbent, SearchBudget& budget,
                    SatOptions options = {});

  void run();
  /// A clique larger than the incumbent (ids of g), or empty when none was found.
  const std::vector<int>& best() const { return best_; }
  /// The number of branching vertices the MaxSAT test took out of B (for the benchmarks).
  long long absorbed() const { return absorbed_; }
  /// The inconsistent subsets relaxed (SatOptions::relax), over all nodes.
  long long relaxed() const { return relaxed_; }
  /// Words touched colouring, over all nodes (what an interleaved local search is budgeted by).
  long long work() const { return work_; }

  /// Hands every node whose candidates are a near-clique to a CoverSearch, as
  /// BranchAndBound::hand_off_near_cliques() does, when it needs at least `min_needed` vertices.
  void hand_off_near_cliques(int min_needed) { cover_min_ = min_needed; }

  /// Runs `search` (a local search on g) interleaved, as BranchAndBound::interleave() does: every
  /// 1,024 nodes it catches up to `initial_work` plus `share` of the colouring's words, and a
  /// larger clique it finds becomes the incumbent.
  void interleave(LocalSearch* search, long long initial_work, double share) {
    helper_ = search;
    helper_initial_ = initial_work;
    helper_share_ = share;
  }

 private:
  void expand(int depth);
  void consult_helper();  // the interleaved local search's turn (interleave())
  int colour(const Word* P, int depth, int kmin);
  int filter(int depth, int count, int low);  // the MaxSAT step; returns |B|
  bool test(int v, int low);  // true when v leaves B (joined, re-numbered or in a conflict)
  bool conflict(int low);     // unit propagation from the units queued; freezes the subset found

  // The node's low classes as the tests see them: each vertex's class, the classes' sizes and
  // their union A. Set once per node; re-numbering and joining keep them.
  void index_classes(int low);
  void join(int v, int k);  // v into class k (a proper colour class after the move)
  // The MaxSAT state of one test is R, the members of unfrozen classes still compatible with the
  // vertices set true, and a count per class of them. Setting a unit true clears its
  // non-neighbours from R a word at a time and walks only those (a few bits a word on dense
  // graphs); the next test rebuilds R from L, so nothing is undone.
  int member(int k) const;  // the first member of class k left in R
  // Re-NUMBER with the test's counts: v has one neighbour u in a class k1, u none in a class k2.
  bool renumber(int v, int low);
  // The first word in [lo_, end_) where low class k holds a neighbour of u; end_ when none does.
  int neighbour_word(int u, int k) const;
  // The last unfrozen low class past k1 holding none of u's neighbours, or k1 when none does.
  int last_class_without(int u, int k1, int low);
  // Propagates the queued units from queue position `from`; returns the emptied class or -1.
  int up_propagate(std::size_t from);
  template <bool kRelax>
  int propagate(std::size_t from);  // up_propagate() with or without relaxation literals
  // Where propagation stops: a class of two members left each of which, set true, propagates to
  // a conflict (IncMaxCLQ's failed literals); returns it with the reasons in marks_, or -1.
  int failed_literal(int low);
  void up_set_unit(int cls);
  void mark_reasons(int cls, std::vector<char>& marks);
  void freeze_pending();  // the classes of the current colour group's subsets leave the tests
  void relax_pending();   // ... or stay, each with one relaxation literal they share
  bool fix_literal(int q, int& emptied);  // q's last member is a relaxation literal: set it
  // Class j loses a member because unit q was set (the reason recorded); true when j is empty.
  bool lose_member(int j, int q);
  void clear_marks();  // marks_ back to none, through marked_

  const BitGraph& g_;
  const int W_;
  int best_size_;
  SearchBudget& budget_;
  int cover_min_ = 0;  // 0 = no hand-off
  LocalSearch* helper_ = nullptr;
  long long helper_initial_ = 0;
  double helper_share_ = 0;
  SatOptions options_;
  long long absorbed_ = 0;
  long long relaxed_ = 0;
  long long work_ = 0;
  std::vector<int> clique_, best_;
  std::vector<std::vector<Word>> levels_;
  NearCliqueScratch cover_scratch_;
  std::vector<std::vector<int>> order_, colour_;
  std::vector<Word> U_, Q_, classes_, A_;
  std::vector<Word> L_, R_;  // A less the frozen classes; the members left in the current test
  std::vector<char> frozen_;
  std::vector<int> pending_;  // classes of the current colour group's inconsistent subsets
  int colours_ = 0, coloured_ = 0, lo_ = 0, end_ = 0;  // words [lo_, end_) hold candidates

  // Per vertex of A: its class (written as colour() colours it, then by join(); a relaxed group's
  // refuted vertices, not in A, take their group's class).
  std::vector<int> class_of_;
  // Per class: its members (a test's first counts); -1 once frozen, and a relaxed class's count
  // includes its relaxation literals.
  std::vector<int> open_;
  std::vector<int> count_;     // per class: members left in R (-1: frozen)
  std::vector<Word> saved_R_;  // failed_literal(): R and the counts before a probe
  std::vector<int> saved_count_;
  std::vector<char> unit_of_;      // per class: queued as a unit
  std::vector<int> queue_;         // classes queued as units, in order
  std::vector<int> reason_head_;   // per class: first reason edge (-1 = none)
  std::vector<int> reason_class_;  // per edge: the unit class that removed vertices
  std::vector<int> reason_owner_;  // per edge: the class it removed them from
  std::vector<int> reason_next_;   // per edge: next edge of the same class
  std::vector<int> stack_;
  std::vector<int> ones_;            // the classes a test leaves one member: the first ones_count_
  std::vector<int> hits_, touched_;  // last_class_without(): per class, u's non-neighbours in it
  int ones_count_ = 0;
  std::vector<char> marks_;
  std::vector<int> marked_;  // the classes marks_ holds

  // Relaxation (SatOptions::relax): classes past the low ones are colour groups' refuted
  // vertices; each relaxation literal lies in the classes of one inconsistent subset and counts
  // as a member of each until a unit sets it for one of them.
  int classes_count_ = 0;                      // low classes plus group classes
  std::vector<char> pend_;                     // per class: in pending_
  std::vector<int> group_refuted_;             // the current group's vertices refuted by a conflict
  std::vector<std::vector<int>> literals_of_;  // per class: its relaxation literals
  std::vector<std::vector<int>> classes_of_;   // per literal: its classes
  std::vector<int> literal_set_;               // per literal: the class it was set for, or -1
  std::vector<int> literals_set_;              // literals set in the current test, in order
};

}  // namespace verifybench::detail
