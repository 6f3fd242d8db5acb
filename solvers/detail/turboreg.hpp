#pragma once
// The exact parts of TurboReg (Yan et al., "TurboReg: TurboClique for Robust and Efficient Point
// Cloud Registration", ICCV 2025; TurboClique and Pivot-Guided Search), on the bitset compatibility
// graph C at the strict threshold tau:
//   - SC2 edge weights G^_ij = C_ij sum_k C_ik C_kj (detail/sc2.hpp; C with its diagonal, so each
//     edge weighs its common neighbours + 2, the authors' zero-diagonal weight + 2: every ranking
//     below is the same);
//   - pivot selection: the K1 edges of largest SC2 weight (ties to the lower (i, j));
//   - Pivot-Guided Search: for a pivot (i, j), the TurboCliques (i, j, k) are its 3-cliques; k
//     ranges over the common neighbours of i and j in the ordered SC2 graph (O2Graph, the upper
//     triangle of G^, so k > j: each triangle belongs to one pivot only, the paper's Unique
//     Assignment Property) or, optionally, in G^ itself; the K2 best by G^_ij + G^_ik + G^_jk
//     (ties to the lower k) are kept;
//   - model selection scores (the authors' IN, MAE, MSE) and the post-refinement of the winner.
#include <algorithm>
#include <atomic>
#include <cmath>
#include <vector>

#include "core/parallel.hpp"
#include "core/rigid_fit.hpp"
#include "core/timer.hpp"
#include "graph/bitgraph.hpp"
#include "solvers/detail/consensus.hpp"
#include "solvers/detail/sc2.hpp"

namespace verifybench::turboreg {

/// A pivot edge i < j and its SC2 weight.
struct Pivot {
  int i = 0, j = 0;
  int weight = 0;
};

/// A TurboClique (i, j, k) of a pivot and its score G^_ij + G^_ik + G^_jk.
struct Clique {
  int i = 0, j = 0, k = 0;
  int score = 0;
};

/// Pivot order: heavier first, then lower (i, j).
inline bool heavier(const Pivot& a, const Pivot& b) {
  if (a.weight != b.weight) return a.weight > b.weight;
  return a.i != b.i ? a.i < b.i : a.j < b.j;
}

/// SC2_ij of Eq. (7) of SC2-PCR for an edge {i, j} (detail/sc2.hpp's sc2_entry): the common
/// neighbours + 2.
inline int edge_weight(const BitGraph& g, int i, int j) {
  return common_count(g.row(i), g.row(j), g.words()) + 2;
}

/// Removes edge {u, v} (the authors' mask of pairs too close to fit a stable motion).
inline void remove_edge(BitGraph& g, int u, int v) {
  g.row(u)[v / BitGraph::kWordBits] &= ~(BitGraph::Word{1} << (v % BitGraph::kWordBits));
  g.row(v)[u / BitGraph::kWordBits] &= ~(BitGraph::Word{1} << (u % BitGraph::kWordBits));
}

/// Calls f(j) for every neighbour j > i of i, ascending.
template <class F>
void for_each_later_neighbour(const BitGraph& g, int i, F&& f) {
  const BitGraph::Word* row = g.row(i);
  for (int w = (i + 1) / BitGraph::kWordBits; w < g.words(); ++w) {
    for (BitGraph::Word bits = row[w]; bits; bits &= bits - 1) {
      const int j = w * BitGraph::kWordBits + __builtin_ctzll(bits);
      if (j > i) f(j);
    }
  }
}

/// PGS pivot selection: the `k1` heaviest edges of G^, heaviest first. Rows are weighed
/// in parallel; the order never depends on the thread count. `stopped` is set (and the pivots
/// are those of the rows weighed so far) when the deadline passed.
inline std::vector<Pivot> select_pivots(const BitGraph& g, int k1, WorkerPool& pool,
                                        SteadyClock::time_point deadline, bool& stopped) {
  const int n = g.size();
  std::vector<std::vector<Pivot>> rows(static_cast<std::size_t>(n));
  std::atomic<bool> late{false};
  pool.parallel_for(n, [&](int i) {
    if (late.load(std::memory_order_relaxed)) return;
    if ((i & 31) == 31 && SteadyClock::now() >= deadline) {
      late = true;
      return;
    }
    auto& row = rows[static_cast<std::size_t>(i)];
    for_each_later_neighbour(g, i, [&](int j) { row.push_back({i, j, edge_weight(g, i, j)}); });
  });
  stopped = late;
  std::vector<Pivot> all;
  for (const auto& row : rows) all.insert(all.end(), row.begin(), row.end());
  const auto keep = std::min(all.size(), static_cast<std::size_t>(std::max(k1, 0)));
  std::partial_sort(all.begin(), all.begin() + static_cast<std::ptrdiff_t>(keep), all.end(),
                    heavier);
  all.resize(keep);
  return all;
}

/// PGS TurboClique search for one pivot: the 3-cliques (i, j, k) with k a common neighbour
/// of i and j (k > j in the ordered graph), the `k2` of highest G^_ij + G^_ik + G^_jk, best first.
inline std::vector<Clique> pivot_cliques(const BitGraph& g, const Pivot& p, int k2, bool ordered) {
  std::vector<Clique> found;
  const BitGraph::Word* a = g.row(p.i);
  const BitGraph::Word* b = g.row(p.j);
  const int first_word = ordered ? (p.j + 1) / BitGraph::kWordBits : 0;
  for (int w = first_word; w < g.words(); ++w) {
    for (BitGraph::Word bits = a[w] & b[w]; bits; bits &= bits - 1) {
      const int k = w * BitGraph::kWordBits + __builtin_ctzll(bits);
      if (ordered && k <= p.j) continue;
      found.push_back({p.i, p.j, k, p.weight + edge_weight(g, p.i, k) + edge_weight(g, p.j, k)});
    }
  }
  const auto keep = std::min(found.size(), static_cast<std::size_t>(std::max(k2, 0)));
  std::partial_sort(found.begin(), found.begin() + static_cast<std::ptrdiff_t>(keep), found.end(),
                    [](const Clique& x, const Clique& y) {
                      return x.score != y.score ? x.score > y.score : x.k < y.k;
                    });
  found.resize(keep);
  return found;
}

/// Model selection metrics of the authors' code: IN = the inlier count, MAE = sum over inliers of
/// (tau - r) / tau, MSE = sum over inliers of (tau - r)^2 / tau^2.
enum class Metric { inliers = 0, mae = 1, mse = 2 };

template <int Dim>
double hypothesis_score(const Correspondences<Dim>& corr, const Rigid<Dim>& T, double tau,
                        Metric metric) {
  double score = 0.0;
  for_each_inlier(corr, T, tau, [&](int i) {
    if (metric == Metric::inliers) {
      score += 1.0;
      return;
    }
    const double r = (T * corr.source.col(i) - corr.target.col(i)).norm();
    const double w = std::max(0.0, tau - r) / tau;
    score += metric == Metric::mae ? w : w * w;
  });
  return score;
}

/// The 3-point least-squares motion of a TurboClique; nullopt when its points are degenerate.
template <int Dim>
std::optional<Rigid<Dim>> clique_motion(const Correspondences<Dim>& corr, const Clique& c) {
  Eigen::Matrix<double, Dim, 3> m, q;
  const int ids[3] = {c.i, c.j, c.k};
  for (int a = 0; a < 3; ++a) {
    m.col(a) = corr.source.col(ids[a]);
    q.col(a) = corr.target.col(ids[a]);
  }
  return fit_rigid_fixed<Dim, 3>(m, q);
}

/// The authors' post-refinement (as SC2-PCR's): refit on the inliers of T weighted
/// 1 / (1 + (r / tau)^2) until their count repeats or `iterations` refits ran.
template <int Dim>
Rigid<Dim> post_refine(const Correspondences<Dim>& corr, Rigid<Dim> T, double tau, int iterations) {
  std::size_t previous = 0;
  for (int it = 0; it < iterations; ++it) {
    const std::vector<int> inliers = consensus_set(corr, T, tau);
    if (inliers.size() == previous || inliers.empty()) break;
    previous = inliers.size();
    std::vector<double> w;
    w.reserve(inliers.size());
    for (int i : inliers) {
      const double r = (T * corr.source.col(i) - corr.target.col(i)).norm() / tau;
      w.push_back(1.0 / (1.0 + r * r));
    }
    const auto refit = fit_rigid(corr, inliers, w);
    if (!refit) break;
    T = *refit;
  }
  return T;
}

}  // namespace verifybench::turboreg
