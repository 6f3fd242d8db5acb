// HBST against brute-force Hamming matching: a database of `n` random 256-bit descriptors (ORB's
// length), 1000 queries that are copies of database entries with 0-24 bits flipped plus 1000
// unrelated ones, threshold 50 bits (the paper's). Counters: recall = share of the queries whose
// brute-force nearest (within the threshold) the matcher returns; time per query.
#include <benchmark/benchmark.h>

#include <map>
#include <random>

#include "frontend/hbst.hpp"

namespace vb = verifybench;

namespace {

struct Workload {
  vb::BinaryDescriptors base{256}, queries{256};
  std::vector<int> truth;
};

const Workload& workload(int n) {
  static std::map<int, Workload> cache;
  auto it = cache.find(n);
  if (it != cache.end()) return it->second;
  Workload& w = cache[n];
  std::mt19937_64 rng(n);
  for (int i = 0; i < n; ++i) {
    auto* row = w.base.add();
    for (int k = 0; k < 4; ++k) row[k] = rng();
  }
  std::uniform_int_distribution<int> pick(0, n - 1), bit(0, 255), flips(0, 24);
  for (int q = 0; q < 2000; ++q) {
    auto* row = w.queries.add();
    if (q < 1000) {
      const int from = pick(rng);
      std::copy(w.base.row(from), w.base.row(from) + 4, row);
      for (int f = flips(rng); f > 0; --f) {
        const int b = bit(rng);
        row[b / 64] ^= std::uint64_t{1} << (b % 64);
      }
    } else {
      for (int k = 0; k < 4; ++k) row[k] = rng();
    }
  }
  for (int q = 0; q < w.queries.size(); ++q) {
    w.truth.push_back(vb::brute_force_nearest(w.base, w.queries.row(q), 50).index);
  }
  return w;
}

void BM_BruteForce(benchmark::State& state) {
  const Workload& w = workload(static_cast<int>(state.range(0)));
  for (auto _ : state) {
    for (int q = 0; q < w.queries.size(); ++q) {
      benchmark::DoNotOptimize(vb::brute_force_nearest(w.base, w.queries.row(q), 50));
    }
  }
  state.counters["recall"] = 1.0;
  state.counters["us_per_query"] = benchmark::Counter(
      static_cast<double>(w.queries.size()),
      benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

void BM_Hbst(benchmark::State& state, bool exact) {
  const Workload& w = workload(static_cast<int>(state.range(0)));
  vb::HbstTree tree(256, vb::HbstParams{static_cast<int>(state.range(1)), 64});
  tree.insert(w.base);
  int found = 0, wanted = 0;
  for (auto _ : state) {
    found = wanted = 0;
    for (int q = 0; q < w.queries.size(); ++q) {
      const auto m = tree.nearest(w.queries.row(q), 50, exact);
      if (w.truth[static_cast<std::size_t>(q)] >= 0) {
        ++wanted;
        found += m.index == w.truth[static_cast<std::size_t>(q)];
      }
    }
  }
  state.counters["recall"] = wanted ? double(found) / wanted : 1.0;
  state.counters["depth"] = tree.depth();
  state.counters["us_per_query"] = benchmark::Counter(
      static_cast<double>(w.queries.size()),
      benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

void Sizes(benchmark::internal::Benchmark* b) {
  for (int n : {1000, 10000, 100000}) b->Args({n, 64});
  b->ArgNames({"n", "leaf"});
  b->Unit(benchmark::kMillisecond);
}

}  // namespace

BENCHMARK(BM_BruteForce)->Apply(Sizes);
BENCHMARK_CAPTURE(BM_Hbst, leaf, false)->Apply(Sizes);
BENCHMARK_CAPTURE(BM_Hbst, exact, true)->Apply(Sizes);
