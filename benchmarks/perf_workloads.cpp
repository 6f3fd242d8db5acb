// The fixed workloads of the instruction-count gate (scripts/perf-gate, issue #16). Each one sets
// up its input outside the measured region, then runs the measured call between callgrind client
// requests, so that `valgrind --tool=callgrind --instr-atstart=no --collect-atstart=no` counts
// exactly that call: no dynamic loader, no generator, no file reading. Every draw is seeded and
// every solver runs at one thread with no effective time limit, so the count is the same on
// every run of the same binary. Outside valgrind the requests are no-ops and the program prints
// the native wall time instead.
//
//   perf_workloads --list                  name, whether it can run here, what it measures
//   perf_workloads NAME                    runs one; prints "NAME check=... native_ms=..."
#include <chrono>
#include <cstdio>
#include <cstring>
#include <exception>
#include <filesystem>
#include <functional>
#include <random>
#include <string>
#include <vector>

#if __has_include(<valgrind/callgrind.h>)
#include <valgrind/callgrind.h>
#define VB_MEASURE_BEGIN()          \
  do {                              \
    CALLGRIND_START_INSTRUMENTATION; \
    CALLGRIND_TOGGLE_COLLECT;       \
  } while (0)
#define VB_MEASURE_END()           \
  do {                             \
    CALLGRIND_TOGGLE_COLLECT;      \
    CALLGRIND_STOP_INSTRUMENTATION; \
  } while (0)
#else
#define VB_MEASURE_BEGIN() ((void)0)
#define VB_MEASURE_END() ((void)0)
#endif

#include "cliques/max_clique.hpp"
#include "datasets/dimacs.hpp"
#include "datasets/dump_format.hpp"
#include "generators/synthetic.hpp"
#include "graph/compatibility_graph.hpp"
#include "harness/builtin.hpp"
#include "harness/harness.hpp"
#include "solvers/registry.hpp"
#ifdef VERIFYBENCH_PERF_FRONTEND
#include "frontend/hbst.hpp"
#endif
#ifdef VERIFYBENCH_PERF_LOOP
#include "generators/lidar.hpp"
#include "loop/sequence.hpp"
#endif

namespace vb = verifybench;
namespace fs = std::filesystem;

namespace {

const std::string kData = VERIFYBENCH_SHARED_DATA;

/// The measured call; returns a check string (the result's size) that the gate records, so a
/// change of the count can be told apart from a change of the answer.
using Measured = std::function<std::string()>;

struct Workload {
  std::string name, description;
  std::function<std::string()> unavailable;  ///< why it cannot run here; empty = it can
  std::function<Measured()> setup;
};

vb::SolverParams one_thread(double eps) {
  vb::SolverParams p;
  p.eps = eps;
  p.inlier_threshold = eps;
  p.threads = 1;
  p.time_limit_s = 1e6;  // valgrind runs 30-40x slower: a limit must never be what stops a search
  return p;
}

template <int Dim>
vb::LabeledSet<Dim> synthetic(int n, double outliers, double noise, std::uint64_t seed) {
  vb::SyntheticParams p;
  p.n = n;
  p.outlier_ratio = outliers;
  p.noise = noise;
  p.seed = seed;
  return vb::make_synthetic<Dim>(p);
}

/// One registered solver on a set built once; check = number of inliers and the status.
template <int Dim>
Measured solve(const std::string& solver, vb::LabeledSet<Dim> set, vb::SolverParams params) {
  vb::register_builtin_solvers();
  auto s = vb::SolverRegistry::create(solver);
  return [s = std::shared_ptr<vb::Solver>(std::move(s)), set = std::move(set), params] {
    const auto r = s->solve(set.corr, params);
    return "inliers=" + std::to_string(r.inliers.size()) + ",status=" + vb::to_string(r.status);
  };
}

/// The default clique solver under the calibrated rule, as the CLI runs it (solve, then the
/// screen of score bounds and the null solves); check = inliers, null draws, screened, accepted.
Measured calibrated_clique(vb::LabeledSet<3> set) {
  vb::register_builtin_solvers();
  const vb::SolverParams p = one_thread(0.1);
  auto solver = std::shared_ptr<vb::Solver>(vb::SolverRegistry::create("clique"));
  return [solver, p, set = std::move(set)] {
    const auto r = vb::evaluate<3>(*solver, "clique", set, p, vb::AcceptParams{}, vb::SuccessCriteria{});
    return "inliers=" + std::to_string(r.inliers) + ",null_draws=" + std::to_string(r.null_draws) +
           ",screened=" + std::to_string(r.null_screened) + ",accepted=" + std::to_string(r.accepted);
  };
}

std::string need_dir(const std::string& path) {
  return fs::exists(path) ? "" : path + " absent";
}

/// A seeded G(n, p) graph: the DIMACS generator's recipe (brock/sanr-like density), always here.
vb::BitGraph random_graph(int n, double p, std::uint64_t seed) {
  vb::BitGraph g(n);
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int a = 0; a < n; ++a)
    for (int b = a + 1; b < n; ++b)
      if (u(rng) < p) g.add_edge(a, b);
  return g;
}

Measured clique_on(vb::BitGraph graph, const std::string& algorithm) {
  vb::register_clique_algorithms();
  const auto& info = vb::CliqueAlgorithms::get(algorithm);
  return [g = std::move(graph), run = info.run] {
    const auto r = run(g, vb::CliqueSearchParams{});
    return "omega=" + std::to_string(r.clique.size()) + (r.optimal ? ",optimal" : ",stopped");
  };
}

#ifdef VERIFYBENCH_PERF_LOOP
/// Two laps of a 100 m x 60 m block in the simulated world, 2D front end, clique and ransac under
/// the count rule, drift odometry: every stage of run_loop once (scans, maps, features,
/// retrieval, verification, pose graphs, APE) on a small excerpt.
vb::LoopConfig loop_excerpt() {
  vb::LoopConfig c;
  c.truth = vb::block_laps(100, 60, 2);
  c.lidar.beams = 32;
  c.lidar.columns = 256;
  c.scan_spacing = 10.0;
  c.maps.map_length = 50.0;
  c.extract.pipeline = "2d";
  c.solvers = {"clique", "ransac"};
  c.params = one_thread(1.0);
  c.accept.rule = vb::AcceptParams::Rule::count;  // the paper's rule: no null solves
  c.threads = 1;
  c.seed = 1;
  return c;
}
#endif

std::vector<Workload> workloads() {
  std::vector<Workload> w;
  w.push_back({"graph_n5000_3d", "correspondence graph, Eq. (1), n = 5000, 90% outliers, 3D",
               [] { return std::string(); }, [] {
                 auto set = synthetic<3>(5000, 0.9, 0.01, 1);
                 return Measured([corr = set.corr] {
                   const auto g = vb::build_compatibility_graph(corr, vb::GraphParams{0.1});
                   return "edges=" + std::to_string(g.edge_count());
                 });
               }});
  w.push_back({"clique_n3000_3d", "default clique solver (graph + search + fit), n = 3000, 95% outliers",
               [] { return std::string(); },
               [] { return solve<3>("clique", synthetic<3>(3000, 0.95, 0.01, 1), one_thread(0.1)); }});
  w.push_back({"clique_near_clique_n2000",
               "default clique solver on a near-clique graph (n = 2000, 50% outliers, noise 0.04)",
               [] { return std::string(); },
               [] { return solve<3>("clique", synthetic<3>(2000, 0.5, 0.04, 1), one_thread(0.1)); }});
  w.push_back({"clique_corr_6614", "default clique solver on the 3DMatch dump corr_6614, eps 0.1 m",
               [] { return need_dir(kData + "/3dmatch/corr_6614"); }, [] {
                 auto dump = vb::read_dump(kData + "/3dmatch/corr_6614");
                 return solve<3>("clique", std::get<vb::LabeledSet<3>>(std::move(dump.set)),
                                 one_thread(0.1));
               }});
  w.push_back({"dimacs_random_120_0.9", "default clique algorithm on a seeded G(120, 0.9)",
               [] { return std::string(); },
               [] { return clique_on(random_graph(120, 0.9, 1), "auto"); }});
  w.push_back({"dimacs_brock200_1", "default clique algorithm on DIMACS brock200_1",
               [] { return need_dir(kData + "/dimacs/brock200_1.clq"); },
               [] { return clique_on(vb::read_dimacs(kData + "/dimacs/brock200_1.clq"), "auto"); }});
  w.push_back({"calibrated_clique_n1000",
               "default clique solver under the calibrated rule (solve + permutation null), n = 1000, 99% outliers",
               [] { return std::string(); },
               [] { return calibrated_clique(synthetic<3>(1000, 0.99, 0.01, 1)); }});
  w.push_back({"calibrated_clique_clear_n2000",
               "default clique solver under the calibrated rule on a clear positive (n = 2000, 50% "
               "outliers): the screen of score bounds decides it, no null solve",
               [] { return std::string(); },
               [] { return calibrated_clique(synthetic<3>(2000, 0.5, 0.01, 1)); }});
  w.push_back({"ransac_10k_n1000", "RANSAC, the paper's fixed 10,000 hypotheses, n = 1000, 90% outliers",
               [] { return std::string(); },
               [] { return solve<3>("ransac", synthetic<3>(1000, 0.9, 0.01, 1), one_thread(0.1)); }});
  w.push_back({"lo_ransac_n1000", "LO-RANSAC (adaptive count), n = 1000, 97% outliers",
               [] { return std::string(); },
               [] { return solve<3>("lo-ransac", synthetic<3>(1000, 0.97, 0.01, 1), one_thread(0.1)); }});
  w.push_back({"jcbb_n1000", "JCBB, n = 1000, 90% outliers", [] { return std::string(); },
               [] { return solve<3>("jcbb", synthetic<3>(1000, 0.9, 0.01, 1), one_thread(0.1)); }});
#ifdef VERIFYBENCH_PERF_FRONTEND
  w.push_back({"matcher_hbst_n10000",
               "HBST: insert 10,000 random 256-bit descriptors, 2000 queries within 50 bits",
               [] { return std::string(); }, [] {
                 auto base = std::make_shared<vb::BinaryDescriptors>(256);
                 auto queries = std::make_shared<vb::BinaryDescriptors>(256);
                 std::mt19937_64 rng(1);
                 for (int i = 0; i < 10000; ++i) {
                   auto* row = base->add();
                   for (int k = 0; k < 4; ++k) row[k] = rng();
                 }
                 std::uniform_int_distribution<int> pick(0, 9999), bit(0, 255), flips(0, 24);
                 for (int q = 0; q < 2000; ++q) {
                   auto* row = queries->add();
                   if (q % 2 == 0) {
                     const auto* from = base->row(pick(rng));
                     std::copy(from, from + 4, row);
                     for (int f = flips(rng); f > 0; --f) {
                       const int b = bit(rng);
                       row[b / 64] ^= std::uint64_t{1} << (b % 64);
                     }
                   } else {
                     for (int k = 0; k < 4; ++k) row[k] = rng();
                   }
                 }
                 return Measured([base, queries] {
                   vb::HbstTree tree(256, vb::HbstParams{64, 64});
                   tree.insert(*base);
                   int found = 0;
                   for (int q = 0; q < queries->size(); ++q)
                     found += tree.nearest(queries->row(q), 50).index >= 0;
                   return "matched=" + std::to_string(found);
                 });
               }});
#endif
#ifdef VERIFYBENCH_PERF_LOOP
  w.push_back({"loop_excerpt_2d",
               "loop closure on a sequence: two laps of a 100 m x 60 m simulated block, 2D, clique + ransac",
               [] { return vb::lidar_available() ? std::string() : std::string("built without Embree"); },
               [] {
                 vb::register_builtin_solvers();
                 return Measured([c = loop_excerpt()] {
                   const auto run = vb::run_loop(c);
                   int accepted = 0;
                   for (const auto& r : run.rows) accepted += r.record.accepted;
                   return "maps=" + std::to_string(run.maps.size()) +
                          ",candidates=" + std::to_string(run.candidates.size()) +
                          ",accepted=" + std::to_string(accepted);
                 });
               }});
#endif
  return w;
}

}  // namespace

int main(int argc, char** argv) {
  const auto all = workloads();
  if (argc == 2 && std::strcmp(argv[1], "--list") == 0) {
    for (const auto& w : all) {
      const std::string why = w.unavailable();
      std::printf("%s\t%s\t%s\n", w.name.c_str(), why.empty() ? "yes" : ("no: " + why).c_str(),
                  w.description.c_str());
    }
    return 0;
  }
  if (argc != 2 || argv[1][0] == '-') {
    std::fprintf(stderr, "usage: perf_workloads --list | perf_workloads NAME\n");
    return 2;
  }
  for (const auto& w : all) {
    if (w.name != argv[1]) continue;
    const std::string why = w.unavailable();
    if (!why.empty()) {
      std::fprintf(stderr, "perf_workloads: %s cannot run here: %s\n", w.name.c_str(), why.c_str());
      return 3;
    }
    try {
      const Measured measured = w.setup();
      const auto start = std::chrono::steady_clock::now();
      VB_MEASURE_BEGIN();
      const std::string check = measured();
      VB_MEASURE_END();
      const double ms =
          std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
      std::printf("%s check=%s native_ms=%.3f\n", w.name.c_str(), check.c_str(), ms);
      return 0;
    } catch (const std::exception& e) {
      std::fprintf(stderr, "perf_workloads: %s: %s\n", w.name.c_str(), e.what());
      return 1;
    }
  }
  std::fprintf(stderr, "perf_workloads: unknown workload '%s' (--list shows them)\n", argv[1]);
  return 2;
}
