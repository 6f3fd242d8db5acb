#pragma once
// Two stages of TEASER (Yang, Shi, Carlone, "TEASER: Fast and Certifiable Point Cloud
// Registration", T-RO 2020) that teaser_solver.cpp composes and the tests check against brute
// force: adaptive voting, the exact solver of scalar truncated least squares behind TEASER's scale
// and component-wise translation estimates, and TEASER++'s k-core inlier selection (KCORE_HEU).
#include <algorithm>
#include <cmath>
#include <optional>
#include <vector>

#include "cliques/max_clique.hpp"

namespace verifybench {

struct VoteResult {
  double estimate = 0.0;  ///< argmin of the TLS cost
  double cost = 0.0;      ///< sum_i min((estimate - x_i)^2 / c^2, 1) at the consensus set's mean
  int consensus = 0;      ///< measurements with |estimate - x_i| <= c
};

/// Adaptive voting (TEASER, scalar TLS by voting): min_x sum_i min((x - x_i)^2 / c^2, cbar^2)
/// with cbar = 1. The 2n interval ends x_i -+ c cut the line into pieces on which the set of
/// intervals holding x -- the consensus set -- is constant; on each, the TLS cost is least at the
/// consensus set's mean, so the best of those means is the global minimum (the paper's theorem on
/// adaptive voting). Sorted, each consensus set is a window of the values; one sweep moves the
/// window's ends, prices it from prefix sums, and prices the windows that may win exactly.
/// O(n log n) plus the exact prices. n >= 1, c > 0.
inline VoteResult adaptive_vote(const std::vector<double>& x, double c) {
  std::vector<double> xs(x);
  std::sort(xs.begin(), xs.end());
  const int n = static_cast<int>(xs.size());
  const double c2 = c * c, shift = xs[static_cast<std::size_t>(n / 2)];
  std::vector<double> p1(xs.size() + 1, 0.0), p2(xs.size() + 1, 0.0);  // shifted prefix sums
  for (std::size_t i = 0; i < xs.size(); ++i) {
    p1[i + 1] = p1[i] + (xs[i] - shift);
    p2[i + 1] = p2[i] + (xs[i] - shift) * (xs[i] - shift);
  }
  const double rounding = 1e-9 * (1.0 + p2.back() / c2);  // bound on the prefix sums' error
  VoteResult best{xs.front(), static_cast<double>(n) + 1.0, 0};
  // Intervals enter at xs_i - c and leave at xs_i + c, both in sorted order: the consensus set
  // right of a position is the window [lo, hi).
  for (int lo = 0, hi = 0; lo < n;) {
    const double at = hi < n ? std::min(xs[static_cast<std::size_t>(hi)] - c,
                                        xs[static_cast<std::size_t>(lo)] + c)
                             : xs[static_cast<std::size_t>(lo)] + c;
    while (hi < n && xs[static_cast<std::size_t>(hi)] - c == at) ++hi;
    while (lo < hi && xs[static_cast<std::size_t>(lo)] + c == at) ++lo;
    const int k = hi - lo;
    if (k == 0) continue;
    const double s1 = p1[static_cast<std::size_t>(hi)] - p1[static_cast<std::size_t>(lo)];
    const double s2 = p2[static_cast<std::size_t>(hi)] - p2[static_cast<std::size_t>(lo)];
    if (std::max(0.0, s2 - s1 * s1 / k) / c2 + (n - k) > best.cost + rounding) continue;
    double mean = 0.0, sse = 0.0;  // exact price of a window that may win
    for (int i = lo; i < hi; ++i) mean += xs[static_cast<std::size_t>(i)];
    mean /= k;
    for (int i = lo; i < hi; ++i) {
      sse += (xs[static_cast<std::size_t>(i)] - mean) * (xs[static_cast<std::size_t>(i)] - mean);
    }
    const double cost = sse / c2 + (n - k);
    if (cost < best.cost) best = {mean, cost, 0};
  }
  for (double v : xs) best.consensus += std::abs(v - best.estimate) <= c;
  return best;
}

/// TEASER++'s KCORE_HEU: the max k-core -- the vertices whose core number is the largest -- when
/// that number exceeds threshold * n (kcore_heuristic_threshold, 0.5 there); nullopt otherwise,
/// where TEASER++ falls back to its heuristic clique.
inline std::optional<std::vector<int>> max_kcore_selection(const BitGraph& g, double threshold) {
  const CoreDecomposition cd = core_decomposition(g);
  if (cd.core.empty()) return std::nullopt;
  const int k = *std::max_element(cd.core.begin(), cd.core.end());
  if (!(k > threshold * g.size())) return std::nullopt;
  std::vector<int> core;
  for (int v = 0; v < g.size(); ++v) {
    if (cd.core[static_cast<std::size_t>(v)] == k) core.push_back(v);
  }
  return core;
}

}  // namespace verifybench
