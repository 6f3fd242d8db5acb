#pragma once
// A dense graph's kernel for maximum clique: the reductions of minimum vertex cover (maximum
// independent set) applied to the complement H, read on G's rows (internal to cliques/). With
// omega(G) = alpha(H) (a clique of G is an independent set of H), each rule keeps
//   omega(G) = omega(kernel) + credit
// and maps every clique of the kernel back to one of G that is `credit` larger:
// - simplicial (Strash 2016's isolated vertex): v's non-neighbours are pairwise non-adjacent in G
//   (with v, a clique of H: v is simplicial there): some maximum clique holds v. v is taken
//   (credit + 1), its non-neighbours dropped.
// - domination (Fomin, Grandoni & Kratsch 2009): u and v non-adjacent with N(u) inside N(v): a
//   clique through u can trade u for v, so u is dropped.
// - folding (Chen, Kanj & Jia 2001): v has exactly two non-neighbours a and b, adjacent to each
//   other. a and b merge into one vertex adjacent to their common neighbours, v is dropped, and
//   credit + 1: a clique through the merged vertex holds a and b instead, one without it holds v.
// They fire where H is sparse: a neighbourhood of balm_realworld's b112_72 FPFH 0.3 k3 (851
// members at density 0.91, needing 322) keeps 708 needing 252 (BENCHMARK.md, section 67). Each
// pass reads every vertex's non-neighbours once; a rule's test stops at the first word that
// fails it.
#include <vector>

#include "cliques/detail/bbmc.hpp"

namespace verifybench::detail {

class CliqueKernel {
 public:
  /// Reduces g until no rule applies (or `max_rounds` passes over the vertices).
  explicit CliqueKernel(const BitGraph& g, int max_rounds = 16);

  /// The reduced graph; its vertex k stands for kept()[k] of g (a merged vertex for the slot it
  /// kept).
  const BitGraph& graph() const { return kernel_; }
  const std::vector<int>& kept() const { return kept_; }
  /// How much larger than the kernel's the clique of g is (taken vertices and folds).
  int credit() const { return credit_; }

  /// The clique of g, `credit()` larger, that a clique of the kernel (its ids) maps back to.
  std::vector<int> lift(const std::vector<int>& kernel_clique) const;

 private:
  struct Step {
    enum Kind { kTake, kFold } kind;
    int v, a, b;  // kTake: v; kFold: v dropped, a kept for a and b, b dropped
  };
  bool alive(int v) const {
    return (alive_[static_cast<std::size_t>(v / kBits)] >> (v % kBits)) & 1;
  }
  void drop(int v) { alive_[static_cast<std::size_t>(v / kBits)] &= ~(Word{1} << (v % kBits)); }
  Word* row(int v) {
    return rows_.data() + static_cast<std::size_t>(v) * static_cast<std::size_t>(W_);
  }
  // v's non-neighbours left (v itself excluded) into out_, their number.
  int non_neighbours(int v);
  bool take_if_simplicial(int v, int count);
  bool drop_if_dominated(int u);
  void fold(int v, int a, int b);

  int n_, W_;
  std::vector<Word> rows_, alive_, out_;
  std::vector<Step> steps_;
  int credit_ = 0;
  std::vector<int> kept_;
  BitGraph kernel_;
};

}  // namespace verifybench::detail
