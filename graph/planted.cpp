// The planted near-cliques of graph/planted.hpp.
#include "graph/planted.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

namespace verifybench {

namespace {

/// The independence number of the vertices in `mask` (<= 32), given each vertex's closed
/// neighbourhood: a vertex with at most one neighbour left joins the set, else the lowest one is
/// branched on (in the set, or not).
int independence_number(const std::vector<std::uint32_t>& closed, std::uint32_t mask) {
  if (mask == 0) return 0;
  for (std::uint32_t m = mask; m; m &= m - 1) {
    const int v = __builtin_ctz(m);
    if (__builtin_popcount(closed[std::size_t(v)] & mask) <= 2) {
      return 1 + independence_number(closed, mask & ~closed[std::size_t(v)]);
    }
  }
  const int v = __builtin_ctz(mask);
  return std::max(independence_number(closed, mask & ~(1u << v)),
                  1 + independence_number(closed, mask & ~closed[std::size_t(v)]));
}

/// A random order of the n vertex ids (K first, then the outliers, in shuffled ids).
std::vector<int> shuffled_ids(int n, std::mt19937_64& rng) {
  std::vector<int> id(static_cast<std::size_t>(n));
  std::iota(id.begin(), id.end(), 0);
  std::shuffle(id.begin(), id.end(), rng);
  return id;
}

/// Each outlier (positions k.. of `id`) sees fewer than omega / 2 random vertices.
void add_outliers(PlantedGraph& nc, int k, const std::vector<int>& id, std::mt19937_64& rng) {
  const int n = static_cast<int>(id.size());
  std::uniform_int_distribution<int> any(0, n - 1);
  for (int o = k; o < n; ++o) {
    for (int e = 0; e < nc.omega / 2 - 1; ++e) {
      nc.g.add_edge(id[std::size_t(o)], id[std::size_t(any(rng))]);
    }
  }
}

/// k >= 1 and outliers >= 0, else std::invalid_argument naming the value.
void check_sizes(int k, int outliers) {
  if (k < 1) throw std::invalid_argument("planted graph: k " + std::to_string(k) + " < 1");
  if (outliers < 0) {
    throw std::invalid_argument("planted graph: outliers " + std::to_string(outliers) + " < 0");
  }
}

constexpr int kMaxHubs = 100;

}  // namespace

PlantedGraph block_near_clique(int k, int outliers, int block, double block_density,
                               std::uint64_t seed) {
  check_sizes(k, outliers);
  if (block < 1 || block > 32) {
    throw std::invalid_argument("planted graph: block " + std::to_string(block) +
                                " outside 1..32 (the oracle works on 32-bit masks)");
  }
  if (!(block_density >= 0.0 && block_density <= 1.0)) {
    throw std::invalid_argument("planted graph: block_density " + std::to_string(block_density) +
                                " outside [0, 1]");
  }
  std::mt19937_64 rng(seed);
  const std::vector<int> id = shuffled_ids(k + outliers, rng);
  PlantedGraph nc{BitGraph(k + outliers)};
  long long missing = 0;
  std::bernoulli_distribution cut(block_density);
  for (int first = 0; first < k; first += block) {
    const int size = std::min(block, k - first);
    std::vector<std::uint32_t> closed(static_cast<std::size_t>(size));  // v and its non-neighbours
    for (int a = 0; a < size; ++a) closed[std::size_t(a)] |= 1u << a;
    for (int a = 0; a < size; ++a) {
      for (int b = a + 1; b < size; ++b) {
        if (cut(rng)) {
          ++missing;
          closed[std::size_t(a)] |= 1u << b;
          closed[std::size_t(b)] |= 1u << a;
        } else {
          nc.g.add_edge(id[std::size_t(first + a)], id[std::size_t(first + b)]);
        }
      }
    }
    nc.omega += independence_number(closed, size == 32 ? ~0u : (1u << size) - 1);
    for (int a = 0; a < size; ++a) {  // every pair across blocks is an edge
      for (int b = first + size; b < k; ++b)
        nc.g.add_edge(id[std::size_t(first + a)], id[std::size_t(b)]);
    }
  }
  nc.removed = static_cast<double>(missing) / (0.5 * k * (k - 1.0));
  add_outliers(nc, k, id, rng);
  return nc;
}

PlantedGraph hub_near_clique(int k, int hubs, int outliers, std::uint64_t seed) {
  check_sizes(k, outliers);
  if (hubs < 0 || hubs > std::min(k, kMaxHubs)) {
    throw std::invalid_argument("planted graph: hubs " + std::to_string(hubs) + " outside 0.." +
                                std::to_string(std::min(k, kMaxHubs)) +
                                " (the oracle enumerates the hubs' cliques)");
  }
  constexpr int kBlock = 12;
  std::mt19937_64 rng(seed);
  const std::vector<int> id = shuffled_ids(k + outliers, rng);
  PlantedGraph nc{BitGraph(k + outliers)};
  BitGraph cut(k);  // K's non-edges (ids 0..k-1: the hubs first, then the blocks in turn)
  std::uniform_real_distribution<double> heavy(0.2, 0.6),
      log_light(std::log(0.001), std::log(0.05));
  std::bernoulli_distribution hub_pair(0.5), block_pair(0.2);
  for (int h = 0; h < hubs; ++h) {
    std::bernoulli_distribution breaks(h % 2 == 0 ? heavy(rng) : std::exp(log_light(rng)));
    for (int v = 0; v < k; ++v) {
      if (v == h) continue;
      if (v < hubs ? hub_pair(rng) : breaks(rng)) cut.add_edge(h, v);
    }
  }
  const int blocks = (k - hubs + kBlock - 1) / kBlock;
  std::vector<std::vector<int>> alpha(static_cast<std::size_t>(blocks));
  for (int b = 0; b < blocks; ++b) {
    const int first = hubs + b * kBlock, size = std::min(kBlock, k - first);
    std::vector<unsigned> closed(static_cast<std::size_t>(size));  // v and its non-neighbours
    for (int a = 0; a < size; ++a) closed[static_cast<std::size_t>(a)] |= 1u << a;
    for (int a = 0; a < size; ++a) {
      for (int c = a + 1; c < size; ++c) {
        if (!block_pair(rng)) continue;
        cut.add_edge(first + a, first + c);
        closed[static_cast<std::size_t>(a)] |= 1u << c;
        closed[static_cast<std::size_t>(c)] |= 1u << a;
      }
    }
    auto& table = alpha[static_cast<std::size_t>(b)];
    table.assign(std::size_t{1} << size, 0);
    for (unsigned X = 1; X < table.size(); ++X) {
      const int v = __builtin_ctz(X);
      table[X] =
          std::max(table[X & ~(1u << v)], 1 + table[X & ~closed[static_cast<std::size_t>(v)]]);
    }
  }
  // Every clique I of the hubs (by increasing id), with the block vertices all of I see.
  std::vector<std::vector<unsigned>> hub_cuts(static_cast<std::size_t>(hubs),
                                              std::vector<unsigned>(std::size_t(blocks), 0));
  for (int h = 0; h < hubs; ++h)
    for (int v = hubs; v < k; ++v)
      if (cut.adjacent(h, v))
        hub_cuts[std::size_t(h)][std::size_t((v - hubs) / kBlock)] |= 1u << ((v - hubs) % kBlock);
  std::vector<unsigned> seen(static_cast<std::size_t>(blocks));
  for (int b = 0; b < blocks; ++b)
    seen[std::size_t(b)] = static_cast<unsigned>(alpha[std::size_t(b)].size() - 1);
  std::vector<int> chosen;
  auto visit = [&](auto&& self, int next) -> void {
    int total = static_cast<int>(chosen.size());
    for (int b = 0; b < blocks; ++b) total += alpha[std::size_t(b)][seen[std::size_t(b)]];
    nc.omega = std::max(nc.omega, total);
    for (int h = next; h < hubs; ++h) {
      bool fits = true;
      for (int c : chosen) fits = fits && !cut.adjacent(c, h);
      if (!fits) continue;
      const std::vector<unsigned> before = seen;
      for (int b = 0; b < blocks; ++b)
        seen[std::size_t(b)] &= ~hub_cuts[std::size_t(h)][std::size_t(b)];
      chosen.push_back(h);
      self(self, h + 1);
      chosen.pop_back();
      seen = before;
    }
  };
  visit(visit, 0);
  long long missing = 0;
  for (int a = 0; a < k; ++a) {
    for (int b = a + 1; b < k; ++b) {
      if (cut.adjacent(a, b)) {
        ++missing;
      } else {
        nc.g.add_edge(id[std::size_t(a)], id[std::size_t(b)]);
      }
    }
  }
  nc.removed = static_cast<double>(missing) / (0.5 * k * (k - 1.0));
  add_outliers(nc, k, id, rng);
  return nc;
}

}  // namespace verifybench
