// Each registered solver on synthetic 3D sets: args are n and the outlier ratio in percent.
#include <benchmark/benchmark.h>

#include "generators/synthetic.hpp"
#include "harness/builtin.hpp"
#include "solvers/registry.hpp"

namespace vb = verifybench;

static void BM_Solver(benchmark::State& state, const std::string& name) {
  vb::register_builtin_solvers();
  vb::SyntheticParams p;
  p.n = static_cast<int>(state.range(0));
  p.outlier_ratio = state.range(1) / 100.0;
  const auto set = vb::make_synthetic<3>(p);
  const auto solver = vb::SolverRegistry::create(name);
  vb::SolverParams params;
  std::size_t inliers = 0;
  for (auto _ : state) {
    const auto r = solver->solve(set.corr, params);
    inliers = r.inliers.size();
    benchmark::DoNotOptimize(inliers);
  }
  state.counters["inliers"] = static_cast<double>(inliers);
}

static void Args(benchmark::internal::Benchmark* b) {
  for (int n : {100, 500, 1000, 2000})
    for (int ratio : {50, 90, 99}) b->Args({n, ratio});
  b->ArgNames({"n", "outliers_pct"});
  b->Unit(benchmark::kMillisecond);
}
BENCHMARK_CAPTURE(BM_Solver, clique, std::string("clique"))->Apply(Args);
BENCHMARK_CAPTURE(BM_Solver, ransac, std::string("ransac"))->Apply(Args);

// The RANSAC family, JCBB and the library peers on one set each (n = 1000, 3D); `ransac` above
// runs the paper's fixed 10,000 hypotheses (target: under 20 ms median, single thread).
static void FamilyArgs(benchmark::internal::Benchmark* b) {
  for (int ratio : {50, 90, 99}) b->Args({1000, ratio});
  b->ArgNames({"n", "outliers_pct"});
  b->Unit(benchmark::kMillisecond);
}
BENCHMARK_CAPTURE(BM_Solver, ransac_adaptive, std::string("ransac-adaptive"))->Apply(FamilyArgs);
BENCHMARK_CAPTURE(BM_Solver, msac, std::string("msac"))->Apply(FamilyArgs);
BENCHMARK_CAPTURE(BM_Solver, lo_ransac, std::string("lo-ransac"))->Apply(FamilyArgs);
BENCHMARK_CAPTURE(BM_Solver, jcbb, std::string("jcbb"))->Apply(FamilyArgs);
// The library RANSACs with settings matched to ours (10,000-hypothesis cap, adaptive exit).
BENCHMARK_CAPTURE(BM_Solver, pcl_ransac, std::string("pcl-ransac"))->Apply(FamilyArgs);
BENCHMARK_CAPTURE(BM_Solver, open3d_ransac, std::string("open3d-ransac"))->Apply(FamilyArgs);
