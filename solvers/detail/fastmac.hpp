#pragma once
// The exact parts of FastMAC (Zhang, Zhang, Wang, Li, "FastMAC: Stochastic Spectral Sampling of
// Correspondence Graph", CVPR 2024), on the bitset compatibility graph C of Eq. (1):
//   - the generalized degree signal: the correspondence graph's weights are second
//     order, W = S (.) (S S) with S = C + I (MAC's graph; detail/sc2.hpp's SC2), and the signal is
//     the weighted degree d = W 1;
//   - its high-frequency part through the graph Laplacian L = diag(d) - W (a high-pass
//     filter): f = L d, f_i = sum_j W_ij (d_i - d_j) (W's diagonal cancels);
//   - stochastic spectral sampling: k correspondences drawn without replacement, each
//     draw with probability proportional to |f_i| (the authors' torch.multinomial), here by
//     Efraimidis-Spirakis keys log(u_i) / |f_i|, the k largest (the same distribution), u_i from
//     one seeded stream in index order;
//   - MAC on the sample (Zhang et al., CVPR 2023, as solvers/mac_solver.cpp): the maximal
//     cliques of the induced subgraph, for each vertex the largest one through it (node-guided
//     selection), each a hypothesis.
#include <atomic>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <random>
#include <vector>

#include "cliques/max_clique.hpp"
#include "core/parallel.hpp"
#include "core/timer.hpp"
#include "graph/bitgraph.hpp"
#include "solvers/detail/sc2.hpp"

namespace verifybench::fastmac {

/// The generalized degree signal and its high-pass response.
struct DegreeSignal {
  std::vector<double> degree;  ///< d_i = sum_j W_ij, W = S (.) (S S), S = C + I
  std::vector<double> high;    ///< f = L d, L = diag(d) - W
};

/// d and L d over rows in parallel (each row's sums in a fixed order: the same values for any
/// thread count); nullopt when the deadline passed.
inline std::optional<DegreeSignal> degree_signal(const BitGraph& g, WorkerPool& pool,
                                                 SteadyClock::time_point deadline) {
  const int n = g.size();
  // W's off-diagonal entries per row (neighbours ascending), kept for the second pass.
  std::vector<std::vector<int>> weights(static_cast<std::size_t>(n));
  DegreeSignal s;
  s.degree.assign(static_cast<std::size_t>(n), 0.0);
  s.high.assign(static_cast<std::size_t>(n), 0.0);
  std::atomic<bool> late{false};
  const auto rows = [&](auto&& body) {
    pool.parallel_for(n, [&](int i) {
      if (late.load(std::memory_order_relaxed)) return;
      if ((i & 31) == 31 && SteadyClock::now() >= deadline) {
        late = true;
        return;
      }
      body(i);
    });
  };
  const auto for_each_neighbour = [&](int i, auto&& f) {
    const BitGraph::Word* row = g.row(i);
    for (int w = 0; w < g.words(); ++w) {
      for (BitGraph::Word bits = row[w]; bits; bits &= bits - 1)
        f(w * BitGraph::kWordBits + __builtin_ctzll(bits));
    }
  };
  rows([&](int i) {
    auto& w = weights[static_cast<std::size_t>(i)];
    double d = g.degree(i) + 1;  // W_ii = deg_i + 1
    for_each_neighbour(i, [&](int j) {
      w.push_back(common_count(g.row(i), g.row(j), g.words()) + 2);  // W_ij, an edge
      d += w.back();
    });
    s.degree[static_cast<std::size_t>(i)] = d;
  });
  if (late) return std::nullopt;
  rows([&](int i) {
    const auto& w = weights[static_cast<std::size_t>(i)];
    const double di = s.degree[static_cast<std::size_t>(i)];
    double f = 0.0;
    std::size_t e = 0;
    for_each_neighbour(i,
                       [&](int j) { f += w[e++] * (di - s.degree[static_cast<std::size_t>(j)]); });
    s.high[static_cast<std::size_t>(i)] = f;
  });
  if (late) return std::nullopt;
  return s;
}

/// k = floor(ratio n) (the authors' int(n ratio)), at least min(n, floor_count): a sample too
/// small to hold one hypothesis of MAC makes none.
inline int sample_size(int n, double ratio, int floor_count) {
  const auto k = static_cast<int>(std::floor(ratio * n));
  return std::min(n, std::max(k, std::min(n, floor_count)));
}

/// u in (0, 1) from the top 53 bits of one 64-bit draw (the same on every standard library).
inline double open_unit(std::mt19937_64& rng) {
  return (static_cast<double>(rng() >> 11) + 0.5) * (1.0 / 9007199254740992.0);
}

/// k indices drawn without replacement, each draw proportional to weight (>= 0), ascending.
/// Zero weights come last, in the order of their own keys. Deterministic for a seed.
inline std::vector<int> weighted_sample(const std::vector<double>& weight, int k,
                                        std::uint64_t seed) {
  const int n = static_cast<int>(weight.size());
  std::mt19937_64 rng(seed);
  struct Key {
    int zero;    // 1 for a zero weight: after every positive one
    double key;  // log(u) / w (positive weights) or log(u)
    int index;
  };
  std::vector<Key> keys(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) {
    const double w = weight[static_cast<std::size_t>(i)];
    const double lu = std::log(open_unit(rng));
    keys[static_cast<std::size_t>(i)] = w > 0.0 ? Key{0, lu / w, i} : Key{1, lu, i};
  }
  k = std::clamp(k, 0, n);
  std::partial_sort(keys.begin(), keys.begin() + k, keys.end(), [](const Key& a, const Key& b) {
    if (a.zero != b.zero) return a.zero < b.zero;
    return a.key != b.key ? a.key > b.key : a.index < b.index;
  });
  std::vector<int> chosen;
  for (int s = 0; s < k; ++s) chosen.push_back(keys[static_cast<std::size_t>(s)].index);
  std::sort(chosen.begin(), chosen.end());
  return chosen;
}

/// The subgraph of g induced by `vertices` (vertex a of it is vertices[a]).
inline BitGraph induced_subgraph(const BitGraph& g, const std::vector<int>& vertices) {
  const int k = static_cast<int>(vertices.size());
  BitGraph sub(k);
  for (int a = 0; a < k; ++a) {
    for (int b = a + 1; b < k; ++b) {
      if (g.adjacent(vertices[static_cast<std::size_t>(a)], vertices[static_cast<std::size_t>(b)]))
        sub.add_edge(a, b);
    }
  }
  return sub;
}

/// MAC's hypotheses (Zhang et al., CVPR 2023; the selection of solvers/mac_solver.cpp): the
/// maximal cliques of at least params.min_size vertices, keeping for every vertex the largest
/// one through it (node-guided selection); the kept cliques in enumeration order.
struct NodeGuidedCliques {
  std::vector<std::vector<int>> cliques;
  bool complete = true;  ///< the enumeration finished (no limit cut it)
  long long nodes = 0;   ///< Bron-Kerbosch nodes expanded
};

inline NodeGuidedCliques node_guided_cliques(const BitGraph& g, const MaximalCliqueParams& params) {
  const int n = g.size();
  std::vector<int> best_size(static_cast<std::size_t>(n), 0),
      best_id(static_cast<std::size_t>(n), -1);
  std::vector<std::vector<int>> kept;
  NodeGuidedCliques out;
  out.complete = for_each_maximal_clique(
      g, params,
      [&](const std::vector<int>& clique) {
        const int size = static_cast<int>(clique.size());
        bool improves = false;
        for (int u : clique) improves |= size > best_size[static_cast<std::size_t>(u)];
        if (!improves) return;
        for (int u : clique) {
          if (size > best_size[static_cast<std::size_t>(u)]) {
            best_size[static_cast<std::size_t>(u)] = size;
            best_id[static_cast<std::size_t>(u)] = static_cast<int>(kept.size());
          }
        }
        kept.push_back(clique);
      },
      &out.nodes);
  std::vector<int> ids(best_id);
  std::sort(ids.begin(), ids.end());
  ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
  for (int id : ids) {
    if (id >= 0) out.cliques.push_back(std::move(kept[static_cast<std::size_t>(id)]));
  }
  return out;
}

}  // namespace verifybench::fastmac
