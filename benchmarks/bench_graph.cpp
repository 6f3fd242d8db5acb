// Correspondence graph construction, Eq. (1): n^2/2 pair tests. Reports pair tests per second.
#include <benchmark/benchmark.h>

#include "generators/synthetic.hpp"
#include "graph/compatibility_graph.hpp"

namespace vb = verifybench;

template <int Dim>
static void BM_CompatibilityGraph(benchmark::State& state) {
  vb::SyntheticParams p;
  p.n = static_cast<int>(state.range(0));
  p.outlier_ratio = 0.9;
  const auto set = vb::make_synthetic<Dim>(p);
  for (auto _ : state) {
    auto g = vb::build_compatibility_graph(set.corr, vb::GraphParams{0.1});
    benchmark::DoNotOptimize(g.row(0));
  }
  const double pairs = 0.5 * double(p.n) * double(p.n - 1);
  state.counters["pairs_per_s"] =
      benchmark::Counter(pairs, benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK_TEMPLATE(BM_CompatibilityGraph, 3)
    ->ArgName("n")
    ->Arg(500)
    ->Arg(2000)
    ->Arg(6614)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_TEMPLATE(BM_CompatibilityGraph, 2)->ArgName("n")->Arg(500)->Arg(2000)->Unit(benchmark::kMillisecond);
