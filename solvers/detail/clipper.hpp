#pragma once
// The stages of the `clipper` solver that the tests check alone, on graphs as well as on
// correspondences:
//   CLIPPER (Lusk, Fathian, How, "CLIPPER: A Graph-Theoretic Framework for Robust Data
//   Association", ICRA 2021): the weighted consistency graph, whose pair scores are
//     s_ij = exp(-c_ij^2 / (2 sigma^2)) when c_ij = | ||m_i - m_j|| - ||q_i - q_j|| | < eps, else
//     0,
//   in an affinity matrix M with ones on the diagonal and a binary constraint matrix C (C_ij = 1
//   when the pair is consistent, C_ii = 1); the densest-subgraph problem
//     max u^T M u / u^T u  over u in {0, 1}^n with u_i u_j = 0 where C_ij = 0,
//   relaxed to the unit sphere's positive orthant with the inconsistent pairs penalised,
//     max u^T (M - d C-bar) u  s.t. ||u|| = 1, u >= 0,      C-bar = 1 1^T - C,
//   solved by projected gradient ascent (a line search per step) while d grows until no
//   inconsistent pair is left in the support of u; the support is the selection.
//   CLIPPER+ (Fathian, Summers, "CLIPPER+: A Fast Maximal Clique Algorithm for Robust Global
//   Registration", RA-L 2024): core numbers (Batagelj-Zaversnik), the paper's Algorithm 1 (a
//   greedy maximal clique grown from each vertex in descending core order), certification when
//   that clique reaches max core + 1, pruning of every vertex whose core number is below the
//   clique's size (it cannot lie in a larger clique), then CLIPPER on the pruned graph started
//   away from the heuristic clique; the larger of the two cliques wins (ties: CLIPPER's).
// The gradient ascent follows the authors' CLIPPER+ code (ariarobotics/clipperp,
// clique_optimization): one power step scales u0, d starts at min_i (M u)_i / (C-bar u)_i over the
// entries where both u_i and (C-bar u)_i are above zero_eps and grows by the same minimum after
// every inner loop, the Armijo line search backtracks by beta and a successful step widens the
// next by 1 / sqrt(beta) within [1e-9, 2], and the rounding keeps u_i > zero_eps.
// The affinity is sparse (CSR rows over the kept vertices), built from the bitset graph's rows:
// never an n x n dense matrix.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <limits>
#include <numeric>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "cliques/max_clique.hpp"
#include "core/correspondences.hpp"
#include "core/timer.hpp"
#include "graph/bitgraph.hpp"

namespace verifybench {

/// CLIPPER's consistency score of a pair whose lengths differ by c: exp(-c^2 / (2 sigma^2)) when
/// c < eps (Eq. (1)'s test, strict as the graph's), else 0.
inline double clipper_score(double c, double eps, double sigma) {
  return c < eps ? std::exp(-0.5 * c * c / (sigma * sigma)) : 0.0;
}

/// c_ij = | ||m_i - m_j|| - ||q_i - q_j|| |, the pair's length difference.
template <int Dim>
double pair_length_difference(const Correspondences<Dim>& corr, int i, int j) {
  return std::abs((corr.source.col(i) - corr.source.col(j)).norm() -
                  (corr.target.col(i) - corr.target.col(j)).norm());
}

/// CLIPPER+ Algorithm 1, the degeneracy-ordered greedy maximal clique: the vertices in descending
/// core number (ties by id); from each vertex v whose core number can still beat the best clique
/// C* (core(v) >= |C*|), grow C = {v} over v's neighbours of core >= |C*|, in the same order,
/// adding each that is adjacent to all of C; keep the largest C. Stops early at max core + 1, the
/// bound no clique exceeds. Empty for an empty graph; a single vertex for a graph without edges.
/// Past `deadline` (read every 64 start vertices) it stops with the best so far and sets *stopped.
inline std::vector<int> clipper_heuristic_clique(
    const BitGraph& g, const CoreDecomposition& cd,
    SteadyClock::time_point deadline = SteadyClock::time_point::max(), bool* stopped = nullptr) {
  const int n = g.size();
  if (n == 0) return {};
  std::vector<int> order(static_cast<std::size_t>(n));
  std::iota(order.begin(), order.end(), 0);
  const auto core = [&](int v) { return cd.core[static_cast<std::size_t>(v)]; };
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return core(a) > core(b); });
  const int bound = core(order.front()) + 1;
  std::vector<int> rank(static_cast<std::size_t>(n));
  for (int r = 0; r < n; ++r)
    rank[static_cast<std::size_t>(order[static_cast<std::size_t>(r)])] = r;

  const int W = g.words();
  std::vector<BitGraph::Word> candidates(static_cast<std::size_t>(W));
  std::vector<int> best, grown, list;
  int started = 0;
  for (int v : order) {
    if ((++started & 63) == 0 && SteadyClock::now() >= deadline) {
      if (stopped) *stopped = true;
      break;
    }
    const int lower = static_cast<int>(best.size());
    if (core(v) < lower) break;  // the order is by descending core: no later vertex can beat it
    list.clear();
    const BitGraph::Word* row = g.row(v);
    for (int w = 0; w < W; ++w) {
      for (BitGraph::Word x = row[w]; x; x &= x - 1) {
        const int u = w * BitGraph::kWordBits + __builtin_ctzll(x);
        if (core(u) >= lower) list.push_back(u);
      }
    }
    if (static_cast<int>(list.size()) + 1 <= lower) continue;
    std::sort(list.begin(), list.end(), [&](int a, int b) {
      return rank[static_cast<std::size_t>(a)] < rank[static_cast<std::size_t>(b)];
    });
    // candidates = the vertices adjacent to every member of C so far.
    std::copy(row, row + W, candidates.begin());
    grown.assign(1, v);
    for (int u : list) {
      if (!((candidates[static_cast<std::size_t>(u / BitGraph::kWordBits)] >>
             (u % BitGraph::kWordBits)) &
            1u))
        continue;
      grown.push_back(u);
      const BitGraph::Word* ru = g.row(u);
      for (int w = 0; w < W; ++w) candidates[static_cast<std::size_t>(w)] &= ru[w];
    }
    if (grown.size() > best.size()) best = grown;
    if (static_cast<int>(best.size()) >= bound) break;
  }
  std::sort(best.begin(), best.end());
  return best;
}

/// CLIPPER+'s pruning: the vertices whose core number is at least `lower` (the `lower`-core; a
/// clique of more than `lower` vertices lies in it), ascending.
inline std::vector<int> clipper_prune(const CoreDecomposition& cd, int lower) {
  std::vector<int> kept;
  for (std::size_t v = 0; v < cd.core.size(); ++v) {
    if (cd.core[v] >= lower) kept.push_back(static_cast<int>(v));
  }
  return kept;
}

/// The affinity of the subgraph on `vertices` (original ids, ascending) in CSR form: row a lists
/// the local ids of vertices[a]'s neighbours among them, ascending, with their scores; M's unit
/// diagonal and C's are implicit. Binary (M = C) when `weights` is empty.
struct ClipperAffinity {
  std::vector<int> vertices;
  std::vector<std::int64_t> offsets;  ///< size() + 1 row starts
  std::vector<int> cols;
  std::vector<double> weights;  ///< one per entry of cols; empty: every score 1
  bool complete = true;         ///< false: the deadline passed while it was built (unusable)

  int size() const { return static_cast<int>(vertices.size()); }
  /// Bytes of a k-vertex affinity with `entries` stored (both directions of each edge).
  static std::size_t bytes_for(std::size_t k, std::size_t entries, bool weighted) {
    return (k + 1) * sizeof(std::int64_t) + k * sizeof(int) + entries * sizeof(int) +
           (weighted ? entries * sizeof(double) : 0);
  }
};

/// Score of the pair of original ids (i, j), i != j, both adjacent in the graph.
using ClipperWeight = std::function<double(int, int)>;

/// Builds the affinity on `vertices` from g's rows; `weight` empty: binary. Throws
/// std::length_error (with the sizes) when it would take more than `max_bytes`; past `deadline`
/// (read every 64 rows) it stops, incomplete.
inline ClipperAffinity clipper_affinity(
    const BitGraph& g, const std::vector<int>& vertices, const ClipperWeight& weight,
    std::size_t max_bytes, SteadyClock::time_point deadline = SteadyClock::time_point::max()) {
  ClipperAffinity a;
  a.vertices = vertices;
  const int k = a.size(), W = g.words();
  std::vector<BitGraph::Word> mask(static_cast<std::size_t>(W), 0);
  std::vector<int> local(static_cast<std::size_t>(g.size()), -1);
  for (int i = 0; i < k; ++i) {
    const int v = vertices[static_cast<std::size_t>(i)];
    mask[static_cast<std::size_t>(v / BitGraph::kWordBits)] |= BitGraph::Word{1}
                                                               << (v % BitGraph::kWordBits);
    local[static_cast<std::size_t>(v)] = i;
  }
  a.offsets.assign(static_cast<std::size_t>(k) + 1, 0);
  const auto past = [&](int i) {
    if ((i & 63) != 63 || SteadyClock::now() < deadline) return false;
    a.complete = false;
    return true;
  };
  for (int i = 0; i < k; ++i) {
    if (past(i)) return a;
    const BitGraph::Word* row = g.row(vertices[static_cast<std::size_t>(i)]);
    std::int64_t degree = 0;
    for (int w = 0; w < W; ++w)
      degree += __builtin_popcountll(row[w] & mask[static_cast<std::size_t>(w)]);
    a.offsets[static_cast<std::size_t>(i) + 1] = a.offsets[static_cast<std::size_t>(i)] + degree;
  }
  const auto entries = static_cast<std::size_t>(a.offsets.back());
  const std::size_t bytes =
      ClipperAffinity::bytes_for(static_cast<std::size_t>(k), entries, static_cast<bool>(weight));
  if (bytes > max_bytes) {
    throw std::length_error("clipper: the affinity of " + std::to_string(k) + " vertices and " +
                            std::to_string(entries) + " entries needs " +
                            std::to_string(bytes >> 20) + " MB beside the graph, over the cap of " +
                            std::to_string(max_bytes >> 20) + " MB (--max-graph-mb)");
  }
  a.cols.resize(entries);
  if (weight) a.weights.resize(entries);
  for (int i = 0; i < k; ++i) {
    if (past(i)) return a;
    const int v = vertices[static_cast<std::size_t>(i)];
    const BitGraph::Word* row = g.row(v);
    auto at = static_cast<std::size_t>(a.offsets[static_cast<std::size_t>(i)]);
    for (int w = 0; w < W; ++w) {
      for (BitGraph::Word x = row[w] & mask[static_cast<std::size_t>(w)]; x; x &= x - 1) {
        const int u = w * BitGraph::kWordBits + __builtin_ctzll(x);
        a.cols[at] = local[static_cast<std::size_t>(u)];
        if (weight) a.weights[at] = v < u ? weight(v, u) : weight(u, v);
        ++at;
      }
    }
  }
  return a;
}

struct ClipperOptimSettings {
  double tol_u = 1e-8;
  double tol_f = 1e-9;
  int max_inner = 200;
  int max_outer = 1000;
  int max_line_search = 20;
  double beta = 0.5;
  double armijo = 0.01;
  double zero_eps = 1e-9;
  double min_alpha = 1e-9;  ///< the step size's floor (CLIPPER+'s minalpha)
  double max_alpha = 2.0;   ///< and ceiling (maxalpha)
  SteadyClock::time_point deadline = SteadyClock::time_point::max();
};

struct ClipperOptimResult {
  std::vector<double> u;   ///< the final u, on the unit sphere, >= 0
  double F = 0.0;          ///< u^T (M - d C-bar) u at the end
  double d = 0.0;          ///< the final penalty
  long long steps = 0;     ///< gradient steps taken in all
  int outer = 0;           ///< values of d used
  bool converged = false;  ///< stopped because no inconsistent pair is left in u's support
  bool timed_out = false;  ///< the deadline cut it short
};

/// CLIPPER's projected gradient ascent with the growing penalty d, from u0 (>= 0, not all zero).
inline ClipperOptimResult clipper_optimize(const ClipperAffinity& a, const std::vector<double>& u0,
                                           const ClipperOptimSettings& s) {
  const int k = a.size();
  const auto K = static_cast<std::size_t>(k);
  ClipperOptimResult r;
  if (k == 0) return r;
  const bool weighted = !a.weights.empty();
  // Mu = M u (unit diagonal) and Cbu = C-bar u = sum(u) - u_i - sum_{j ~ i} u_j, in one pass.
  const auto apply = [&](const std::vector<double>& u, std::vector<double>& Mu,
                         std::vector<double>& Cbu) {
    double total = 0.0;
    for (double x : u) total += x;
    for (std::size_t i = 0; i < K; ++i) {
      double weighted_sum = 0.0, plain = 0.0;
      const auto end = static_cast<std::size_t>(a.offsets[i + 1]);
      for (auto e = static_cast<std::size_t>(a.offsets[i]); e < end; ++e) {
        const double uj = u[static_cast<std::size_t>(a.cols[e])];
        plain += uj;
        if (weighted) weighted_sum += a.weights[e] * uj;
      }
      Mu[i] = u[i] + (weighted ? weighted_sum : plain);
      Cbu[i] = total - u[i] - plain;
    }
  };
  const auto normalize = [](std::vector<double>& v) {
    double norm = 0.0;
    for (double x : v) norm += x * x;
    norm = std::sqrt(norm);
    if (norm > 0.0)
      for (double& x : v) x /= norm;
  };
  // Smallest (M u)_i / (C-bar u)_i over the entries where u_i and (C-bar u)_i are above zero;
  // negative when there is none.
  const auto d_step = [&](const std::vector<double>& u, const std::vector<double>& Mu,
                          const std::vector<double>& Cbu) {
    double best = -1.0;
    for (std::size_t i = 0; i < K; ++i) {
      if (Cbu[i] > s.zero_eps && u[i] > s.zero_eps) {
        const double q = std::abs(Mu[i] / Cbu[i]);
        if (best < 0.0 || q < best) best = q;
      }
    }
    return best;
  };
  std::vector<double> u(K), Mu(K), Cbu(K), grad(K), unew(K), Munew(K), Cbunew(K), gradnew(K);
  // One power step scales u0 (CLIPPER: after it, different u0's look alike).
  {
    std::vector<double> u0n(u0);
    normalize(u0n);
    apply(u0n, u, Cbu);
    normalize(u);
  }
  apply(u, Mu, Cbu);
  double d = std::max(0.0, d_step(u, Mu, Cbu));
  // grad = (M - d C-bar) u projected onto the sphere's tangent plane at u; F = u^T (M - d C-bar) u.
  const auto gradient = [&](const std::vector<double>& x, const std::vector<double>& Mx,
                            const std::vector<double>& Cbx, std::vector<double>& g) {
    double F = 0.0;
    for (std::size_t i = 0; i < K; ++i) {
      g[i] = Mx[i] - d * Cbx[i];
      F += x[i] * g[i];
    }
    for (std::size_t i = 0; i < K; ++i) g[i] -= F * x[i];
    return F;
  };
  double F = gradient(u, Mu, Cbu, grad);
  double alpha = 1.0;
  for (r.outer = 0; r.outer < s.max_outer; ++r.outer) {
    for (int j = 0; j < s.max_inner; ++j) {
      if (SteadyClock::now() >= s.deadline) {
        r.timed_out = true;
        break;
      }
      double Fnew = F, deltaF = 0.0;
      for (int ls = 0; ls < s.max_line_search; ++ls) {
        for (std::size_t i = 0; i < K; ++i) unew[i] = std::max(0.0, u[i] + alpha * grad[i]);
        normalize(unew);
        apply(unew, Munew, Cbunew);
        Fnew = gradient(unew, Munew, Cbunew, gradnew);
        deltaF = Fnew - F;
        double predicted = 0.0;
        for (std::size_t i = 0; i < K; ++i) predicted += grad[i] * (unew[i] - u[i]);
        if (deltaF >= s.armijo * predicted) {
          alpha /= std::sqrt(s.beta);  // accepted: try a longer step next time
          break;
        }
        alpha *= s.beta;  // backtrack
      }
      alpha = std::clamp(alpha, s.min_alpha, s.max_alpha);
      double deltau = 0.0;
      for (std::size_t i = 0; i < K; ++i) deltau += (unew[i] - u[i]) * (unew[i] - u[i]);
      deltau = std::sqrt(deltau);
      // As the authors' code: the last trial step is taken even when the search ran out.
      u.swap(unew);
      Mu.swap(Munew);
      Cbu.swap(Cbunew);
      grad.swap(gradnew);
      F = Fnew;
      ++r.steps;
      if (deltau < s.tol_u || std::abs(deltaF) < s.tol_f) break;
    }
    if (r.timed_out) break;
    const double step = d_step(u, Mu, Cbu);
    if (step < 0.0) {
      r.converged = true;
      break;
    }
    d += step;
    F = gradient(u, Mu, Cbu, grad);
  }
  r.u = std::move(u);
  r.F = F;
  r.d = d;
  return r;
}

/// The rounding: the local ids with u_i > zero_eps, made a clique of g by keeping them in
/// descending u (ties by id) while each is adjacent to all kept before it. On a converged run the
/// support is a clique already (an inconsistent pair i, j in it would leave (C-bar u)_i >= u_j >
/// zero_eps) and is kept whole; the greedy pass only guards runs cut short by a cap or the
/// deadline. Original ids, ascending.
inline std::vector<int> clipper_round(const BitGraph& g, const ClipperAffinity& a,
                                      const std::vector<double>& u, double zero_eps) {
  std::vector<int> support;
  for (int i = 0; i < a.size(); ++i) {
    if (u[static_cast<std::size_t>(i)] > zero_eps) support.push_back(i);
  }
  std::stable_sort(support.begin(), support.end(), [&](int x, int y) {
    return u[static_cast<std::size_t>(x)] > u[static_cast<std::size_t>(y)];
  });
  std::vector<int> clique;
  for (int i : support) {
    const int v = a.vertices[static_cast<std::size_t>(i)];
    bool fits = true;
    for (int c : clique) fits = fits && g.adjacent(c, v);
    if (fits) clique.push_back(v);
  }
  std::sort(clique.begin(), clique.end());
  return clique;
}

struct ClipperSettings {
  ClipperOptimSettings optim;
  bool kcore = true;       ///< CLIPPER+ (heuristic clique, certification, pruning); else CLIPPER
  std::uint64_t seed = 1;  ///< CLIPPER's random u0 (kcore off)
  std::size_t max_bytes = std::numeric_limits<std::size_t>::max();  ///< cap of the affinity
};

struct ClipperSelection {
  std::vector<int> clique;     ///< the selection, ascending; a clique of g
  std::vector<int> heuristic;  ///< Algorithm 1's clique (kcore), ascending
  int max_core = -1;           ///< the graph's max core number (kcore), else -1
  bool certified = false;      ///< the clique reached max core + 1: a maximum clique
  int pruned_size = 0;         ///< vertices CLIPPER ran on (0: it did not run)
  bool optimized = false;      ///< the selection is CLIPPER's clique, not the heuristic's
  ClipperOptimResult optim;    ///< CLIPPER's run, when it ran
  bool timed_out = false;
};

/// CLIPPER+ (kcore) or CLIPPER on g; `weight` empty: the unweighted affinity.
inline ClipperSelection clipper_select(const BitGraph& g, const ClipperSettings& s,
                                       const ClipperWeight& weight) {
  ClipperSelection out;
  const int n = g.size();
  if (n == 0) return out;
  std::vector<int> kept;
  std::vector<double> u0;
  if (s.kcore) {
    const CoreDecomposition cd = core_decomposition(g);
    out.max_core = *std::max_element(cd.core.begin(), cd.core.end());
    bool stopped = false;
    out.heuristic = clipper_heuristic_clique(g, cd, s.optim.deadline, &stopped);
    out.clique = out.heuristic;
    if (stopped) {
      out.timed_out = true;
      return out;
    }
    if (static_cast<int>(out.heuristic.size()) == out.max_core + 1) {
      out.certified = true;  // no clique is larger than max core + 1
      return out;
    }
    kept = clipper_prune(cd, static_cast<int>(out.heuristic.size()));
    // u0: ones away from the heuristic clique, which CLIPPER should not merely find again.
    u0.assign(kept.size(), 1.0);
    bool away = false;
    for (std::size_t i = 0, h = 0; i < kept.size(); ++i) {
      while (h < out.heuristic.size() && out.heuristic[h] < kept[i]) ++h;
      if (h < out.heuristic.size() && out.heuristic[h] == kept[i]) {
        u0[i] = 0.0;
      } else {
        away = true;
      }
    }
    if (!away) return out;  // nothing but the heuristic clique survives the pruning
  } else {
    kept.resize(static_cast<std::size_t>(n));
    std::iota(kept.begin(), kept.end(), 0);
    std::mt19937_64 rng(s.seed);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    u0.resize(kept.size());
    for (double& x : u0) x = unit(rng);
  }
  if (SteadyClock::now() >= s.optim.deadline) {
    out.timed_out = true;
    return out;
  }
  const ClipperAffinity a = clipper_affinity(g, kept, weight, s.max_bytes, s.optim.deadline);
  if (!a.complete) {
    out.timed_out = true;
    return out;
  }
  out.pruned_size = a.size();
  out.optim = clipper_optimize(a, u0, s.optim);
  out.timed_out = out.optim.timed_out;
  std::vector<int> found = clipper_round(g, a, out.optim.u, s.optim.zero_eps);
  if (found.size() >= out.clique.size()) {
    out.clique = std::move(found);
    out.optimized = true;
  }
  if (out.max_core >= 0 && static_cast<int>(out.clique.size()) == out.max_core + 1)
    out.certified = true;
  return out;
}

}  // namespace verifybench
