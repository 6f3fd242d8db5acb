// Each of our exact clique algorithms on correspondence graphs: synthetic 3D sets (args: n, outlier
// ratio in percent) and, when ../shared/data is present, the 3DMatch corr_6614 dump at eps 0.1 m;
// and on planted near-cliques with 1-5% of their pairs removed (graph/planted.hpp, the graphs of
// the test NearCliquesWithOneToFivePercentRemovedMatchTheirHubOracle; arg: k).
// The graph is built once per benchmark; only the search is timed.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <filesystem>
#include <numeric>
#include <random>

#include "cliques/detail/bbmc.hpp"
#include "cliques/max_clique.hpp"
#include "datasets/text_dump.hpp"
#include "generators/synthetic.hpp"
#include "graph/compatibility_graph.hpp"
#include "graph/planted.hpp"

namespace vb = verifybench;

static void run_search(benchmark::State& state, const std::string& algorithm,
                       const vb::BitGraph& g) {
  vb::register_clique_algorithms();
  const auto& info = vb::CliqueAlgorithms::get(algorithm);
  std::size_t omega = 0;
  long long nodes = 0;
  for (auto _ : state) {
    const auto r = info.run(g, {});
    omega = r.clique.size();
    nodes = r.nodes;
  }
  state.counters["omega"] = static_cast<double>(omega);
  state.counters["nodes"] = static_cast<double>(nodes);
}

static void BM_Synthetic(benchmark::State& state, const std::string& algorithm) {
  vb::SyntheticParams p;
  p.n = static_cast<int>(state.range(0));
  p.outlier_ratio = state.range(1) / 100.0;
  const auto set = vb::make_synthetic<3>(p);
  run_search(state, algorithm, vb::build_compatibility_graph(set.corr, vb::GraphParams{0.1}));
}

static void BM_Dump6614(benchmark::State& state, const std::string& algorithm) {
  const std::string dir = VERIFYBENCH_SHARED_DATA "/3dmatch/corr_6614";
  if (!std::filesystem::exists(dir + "/corr.txt")) {
    state.SkipWithError("shared data absent");
    return;
  }
  const auto set = std::get<vb::LabeledSet<3>>(vb::read_text_dump(dir));
  run_search(state, algorithm, vb::build_compatibility_graph(set.corr, vb::GraphParams{0.1}));
}

static void BM_HubNearClique(benchmark::State& state, const std::string& algorithm) {
  const int k = static_cast<int>(state.range(0));
  const vb::PlantedGraph planted =
      vb::hub_near_clique(k, k == 500 ? 50 : 70, k == 3000 ? 1500 : k, 12 + k);
  run_search(state, algorithm, planted.g);
  state.counters["omega_planted"] = planted.omega;
  state.counters["removed_pct"] = 100.0 * planted.removed;
}

static void Args(benchmark::internal::Benchmark* b) {
  for (int n : {1000, 5000})
    for (int ratio : {50, 90, 99}) b->Args({n, ratio});
  b->ArgNames({"n", "outliers_pct"});
  b->Unit(benchmark::kMillisecond);
}

#define VB_CLIQUE_BENCH(name, algorithm)                                      \
  BENCHMARK_CAPTURE(BM_Synthetic, name, std::string(algorithm))->Apply(Args); \
  BENCHMARK_CAPTURE(BM_Dump6614, name, std::string(algorithm))->Unit(benchmark::kMillisecond)

VB_CLIQUE_BENCH(bbmc, "bbmc");
VB_CLIQUE_BENCH(bbmcr, "bbmcr");
VB_CLIQUE_BENCH(bbmcx, "bbmcx");
VB_CLIQUE_BENCH(bbmcx_ls, "bbmcx-ls");
VB_CLIQUE_BENCH(bbmc_kcore, "bbmc-kcore");
VB_CLIQUE_BENCH(bbmc_dec, "bbmc-dec");
// The Russian doll search only on the synthetic sets: it needs about a minute on the dump (285 M
// nodes; its prefix bounds prune little on correspondence graphs).
BENCHMARK_CAPTURE(BM_Synthetic, doll, std::string("doll"))->Apply(Args);
VB_CLIQUE_BENCH(greedy, "greedy");
// Near-cliques: the colouring searches prove k = 500 and run past a minute from k = 1000 on.
BENCHMARK_CAPTURE(BM_HubNearClique, auto, std::string("auto")) -> Arg(500) -> Arg(1000) -> Arg(3000)
    -> ArgName("k") -> Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_HubNearClique, cover, std::string("cover"))
    ->Arg(500)
    ->Arg(1000)
    ->Arg(3000)
    ->ArgName("k")
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_HubNearClique, bbmc, std::string("bbmc"))
    ->Arg(500)
    ->ArgName("k")
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_HubNearClique, bbmcx, std::string("bbmcx"))
    ->Arg(500)
    ->ArgName("k")
    ->Unit(benchmark::kMillisecond);

// Relabelling a graph (detail::permuted, what the decomposition's recolouring does each round on
// its near-clique neighbourhoods): a whole shuffled order of G(n, p); args: n, density in
// thousandths. Scattered bits on sparse rows, 64 x 64 blocks transposed on dense ones, the
// non-edges cleared on near-complete ones.
static void BM_Permuted(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const double p = state.range(1) / 1000.0;
  std::mt19937_64 rng(59);
  std::bernoulli_distribution edge(p);
  vb::BitGraph g(n);
  for (int u = 0; u < n; ++u)
    for (int v = u + 1; v < n; ++v)
      if (edge(rng)) g.add_edge(u, v);
  std::vector<int> order(static_cast<std::size_t>(n));
  std::iota(order.begin(), order.end(), 0);
  std::shuffle(order.begin(), order.end(), rng);
  for (auto _ : state) {
    const vb::BitGraph h = vb::detail::permuted(g, order);
    benchmark::DoNotOptimize(h.row(0));
  }
}
BENCHMARK(BM_Permuted)
    ->ArgsProduct({{500, 2000}, {100, 500, 900, 980}})
    ->ArgNames({"n", "density_permil"})
    ->Unit(benchmark::kMicrosecond);
