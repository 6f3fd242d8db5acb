// Exact maximum clique on the shared DIMACS graphs where cliquer is at its strongest: our
// algorithms against cliquer's own search, both in this process (the peer `cliquer` of the harness
// runs in a forked child, whose fork and graph copy its timings include; here cliquer's graph is
// built once, outside the timed loop, so only clique_unweighted_find_single is timed).
// Skips when ../shared/data/dimacs is absent.
#include <benchmark/benchmark.h>

#include <cstdio>
#include <exception>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "cliques/detail/cliquer_shim.h"
#include "cliques/max_clique.hpp"
#include "datasets/dimacs.hpp"

namespace vb = verifybench;

namespace {

const std::string kDir = VERIFYBENCH_SHARED_DATA "/dimacs/";

void report(benchmark::State& state, std::size_t omega, long long nodes) {
  state.counters["omega"] = static_cast<double>(omega);
  state.counters["nodes"] = static_cast<double>(nodes);
}

void BM_Ours(benchmark::State& state, std::shared_ptr<const vb::BitGraph> graph,
             const std::string& algorithm) {
  const vb::BitGraph& g = *graph;
  const auto& info = vb::CliqueAlgorithms::get(algorithm);
  vb::CliqueSearchResult r;
  for (auto _ : state) r = info.run(g, {});
  report(state, r.clique.size(), r.nodes);
}

void BM_Cliquer(benchmark::State& state, std::shared_ptr<const vb::BitGraph> graph) {
  const vb::BitGraph& g = *graph;
  // The rows are contiguous, n rows of words() words (BitGraph::row).
  const std::unique_ptr<vb_cliquer_graph, void (*)(vb_cliquer_graph*)> handle(
      vb_cliquer_graph_new(g.size(), reinterpret_cast<const unsigned long long*>(g.row(0)),
                           g.words()),
      vb_cliquer_graph_free);
  if (!handle) {
    state.SkipWithError("cliquer could not allocate");
    return;
  }
  std::vector<int> clique(static_cast<std::size_t>(g.size()));
  int size = 0;
  for (auto _ : state) size = vb_cliquer_solve(handle.get(), clique.data());
  report(state, static_cast<std::size_t>(size), 0);
}

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (!std::filesystem::exists(kDir + "MANIFEST.tsv")) {
    std::fprintf(stderr, "bench_dimacs: %s absent, nothing to run\n", kDir.c_str());
    return 0;
  }
  vb::register_clique_algorithms();
  for (const char* name : {"hamming8-4", "johnson16-2-4", "keller4", "brock200_2", "p_hat300-1",
                           "p_hat500-1", "c-fat500-10", "hamming8-2", "san200_0.9_1"}) {
    std::shared_ptr<const vb::BitGraph> graph;
    try {
      graph = std::make_shared<const vb::BitGraph>(vb::read_dimacs(kDir + name + ".clq"));
    } catch (const std::exception& e) {
      std::fprintf(stderr, "bench_dimacs: %s\n", e.what());
      return 1;
    }
    for (const char* algorithm : {"doll", "bbmc", "bbmcx", "bbmc-dec"}) {
      benchmark::RegisterBenchmark((std::string(name) + "/" + algorithm).c_str(), BM_Ours, graph,
                                   std::string(algorithm))
          ->Unit(benchmark::kMillisecond);
    }
    benchmark::RegisterBenchmark((std::string(name) + "/cliquer").c_str(), BM_Cliquer, graph)
        ->Unit(benchmark::kMillisecond);
  }
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
