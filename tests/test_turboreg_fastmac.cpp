// TurboReg and FastMAC against oracles: TurboReg's pivot ranking against the SC2 matrix built by
// triple loops and sorted, its pivot-guided search against every triangle of the graph found by
// exhaustive enumeration (the same pivot rule applied to both); FastMAC's degree signal and its
// Laplacian response against dense matrix products, its sampler's size, seeding and inclusion
// probabilities against the exact ones of successive weighted draws; and both recover motions
// this test draws in their papers' regimes, with the same answer for 1 and 2 threads.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iostream>
#include <limits>
#include <random>
#include <set>
#include <tuple>

#include "core/metrics.hpp"
#include "core/parallel.hpp"
#include "generators/synthetic.hpp"
#include "graph/compatibility_graph.hpp"
#include "registered_solvers.hpp"
#include "solvers/detail/fastmac.hpp"
#include "solvers/detail/turboreg.hpp"
#include "solvers/registry.hpp"
#include "test_util.hpp"

namespace verifybench {
namespace {

using Matrix = std::vector<std::vector<long long>>;

/// S = C + I of a graph, dense.
Matrix with_diagonal(const BitGraph& g) {
  const int n = g.size();
  Matrix s(static_cast<std::size_t>(n), std::vector<long long>(static_cast<std::size_t>(n), 0));
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) s[i][j] = i == j || g.adjacent(i, j);
  return s;
}

/// SC2 = S (.) (S S) by triple loops.
Matrix sc2_by_loops(const BitGraph& g) {
  const Matrix s = with_diagonal(g);
  const std::size_t n = s.size();
  Matrix w(n, std::vector<long long>(n, 0));
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = 0; j < n; ++j) {
      long long ss = 0;
      for (std::size_t k = 0; k < n; ++k) ss += s[i][k] * s[k][j];
      w[i][j] = s[i][j] * ss;
    }
  }
  return w;
}

// ---------------------------------------------------------------------------------------------
// TurboReg

TEST(TurboReg, PivotRankingMatchesTheSortedSc2Matrix) {
  std::mt19937_64 rng(21);
  for (int trial = 0; trial < 40; ++trial) {
    const int n = 8 + trial * 2;
    BitGraph g = test::random_graph(n, 0.1 + 0.6 * (trial % 5) / 4.0, rng);
    if (trial % 3 == 0) test::plant_clique(g, std::min(n, 6 + trial / 5), rng);
    const Matrix w = sc2_by_loops(g);
    std::vector<std::tuple<long long, int, int>> oracle;  // (-weight, i, j): ascending = ranking
    for (int i = 0; i < n; ++i)
      for (int j = i + 1; j < n; ++j)
        if (g.adjacent(i, j)) oracle.emplace_back(-w[i][j], i, j);
    std::sort(oracle.begin(), oracle.end());
    for (int threads : {1, 2}) {
      WorkerPool pool(threads);
      for (int k1 : {1, 5, 40, 1 << 20}) {
        bool stopped = true;
        const auto pivots =
            turboreg::select_pivots(g, k1, pool, SteadyClock::time_point::max(), stopped);
        EXPECT_FALSE(stopped);
        ASSERT_EQ(pivots.size(), std::min<std::size_t>(oracle.size(), k1)) << trial;
        for (std::size_t p = 0; p < pivots.size(); ++p) {
          EXPECT_EQ(
              std::make_tuple(-static_cast<long long>(pivots[p].weight), pivots[p].i, pivots[p].j),
              oracle[p])
              << "trial " << trial << " rank " << p;
        }
      }
    }
  }
}

/// Every triangle (i, j, k) whose pivot is (i, j): k > j in the ordered graph, any other
/// common neighbour in the full one; by exhaustive enumeration of vertex triples, with the score
/// from the triple-loop SC2 matrix, best first (ties to the lower k).
std::vector<turboreg::Clique> oracle_cliques(const BitGraph& g, const Matrix& w, int i, int j,
                                             bool ordered) {
  std::vector<turboreg::Clique> out;
  for (int k = 0; k < g.size(); ++k) {
    if (k == i || k == j || (ordered && k < j)) continue;
    if (g.adjacent(i, j) && g.adjacent(i, k) && g.adjacent(j, k))
      out.push_back({i, j, k, static_cast<int>(w[i][j] + w[i][k] + w[j][k])});
  }
  std::sort(out.begin(), out.end(), [](const auto& a, const auto& b) {
    return a.score != b.score ? a.score > b.score : a.k < b.k;
  });
  return out;
}

TEST(TurboReg, PivotGuidedSearchFindsEveryTriangleOnce) {
  // With every edge a pivot and no cap per pivot, the ordered search must list each triangle of
  // the graph exactly once (the Unique Assignment Property), and the full one each three times.
  std::mt19937_64 rng(5);
  for (int trial = 0; trial < 30; ++trial) {
    const int n = 6 + trial;
    BitGraph g = test::random_graph(n, 0.15 + 0.5 * (trial % 4) / 3.0, rng);
    std::set<std::tuple<int, int, int>> triangles;
    for (int a = 0; a < n; ++a)
      for (int b = a + 1; b < n; ++b)
        for (int c = b + 1; c < n; ++c)
          if (g.adjacent(a, b) && g.adjacent(a, c) && g.adjacent(b, c)) triangles.insert({a, b, c});
    WorkerPool pool(1);
    bool stopped = false;
    const auto pivots =
        turboreg::select_pivots(g, 1 << 20, pool, SteadyClock::time_point::max(), stopped);
    for (bool ordered : {true, false}) {
      std::multiset<std::tuple<int, int, int>> found;
      for (const auto& p : pivots) {
        for (const auto& c : turboreg::pivot_cliques(g, p, n, ordered)) {
          std::array<int, 3> v{c.i, c.j, c.k};
          std::sort(v.begin(), v.end());
          found.insert({v[0], v[1], v[2]});
        }
      }
      EXPECT_EQ(found.size(), triangles.size() * (ordered ? 1 : 3)) << trial;
      for (const auto& t : triangles) EXPECT_EQ(found.count(t), ordered ? 1u : 3u) << trial;
    }
  }
}

TEST(TurboReg, EachPivotKeepsItsBestTrianglesByTheSc2Score) {
  std::mt19937_64 rng(9);
  for (int trial = 0; trial < 30; ++trial) {
    const int n = 10 + trial;
    BitGraph g = test::random_graph(n, 0.3 + 0.4 * (trial % 3) / 2.0, rng);
    const Matrix w = sc2_by_loops(g);
    WorkerPool pool(1);
    bool stopped = false;
    const auto pivots =
        turboreg::select_pivots(g, 1 << 20, pool, SteadyClock::time_point::max(), stopped);
    for (bool ordered : {true, false}) {
      for (int k2 : {1, 2, 3}) {
        for (const auto& p : pivots) {
          auto expected = oracle_cliques(g, w, p.i, p.j, ordered);
          if (expected.size() > static_cast<std::size_t>(k2)) expected.resize(k2);
          const auto got = turboreg::pivot_cliques(g, p, k2, ordered);
          ASSERT_EQ(got.size(), expected.size()) << trial;
          for (std::size_t r = 0; r < got.size(); ++r) {
            EXPECT_EQ(got[r].k, expected[r].k) << trial << " pivot " << p.i << "," << p.j;
            EXPECT_EQ(got[r].score, expected[r].score);
          }
        }
      }
    }
  }
}

// ---------------------------------------------------------------------------------------------
// FastMAC

TEST(FastMac, DegreeSignalAndItsLaplacianResponseMatchDenseProducts) {
  std::mt19937_64 rng(13);
  for (int trial = 0; trial < 24; ++trial) {
    BitGraph g;
    if (trial % 2 == 0) {
      g = test::random_graph(5 + 3 * trial, 0.1 + 0.7 * (trial % 4) / 3.0, rng);
    } else {  // a correspondence graph of Eq. (1)
      SyntheticParams p;
      p.n = 40;
      p.outlier_ratio = 0.5;
      p.extent = 2.0;
      p.seed = static_cast<std::uint64_t>(trial);
      g = build_compatibility_graph(make_synthetic<3>(p).corr, GraphParams{0.1});
    }
    // W = S (.) (S S), d = W 1, L = diag(d) - W, f = L d: dense, by definition.
    const Matrix w = sc2_by_loops(g);
    const std::size_t n = w.size();
    std::vector<long long> d(n, 0);
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = 0; j < n; ++j) d[i] += w[i][j];
    std::vector<long long> f(n, 0);
    for (std::size_t i = 0; i < n; ++i) {
      for (std::size_t j = 0; j < n; ++j) {
        const long long l = (i == j ? d[i] : 0) - w[i][j];
        f[i] += l * d[j];
      }
    }
    for (int threads : {1, 2}) {
      WorkerPool pool(threads);
      const auto s = fastmac::degree_signal(g, pool, SteadyClock::time_point::max());
      ASSERT_TRUE(s.has_value());
      for (std::size_t i = 0; i < n; ++i) {
        EXPECT_EQ(s->degree[i], static_cast<double>(d[i])) << trial << " " << i;
        EXPECT_EQ(s->high[i], static_cast<double>(f[i])) << trial << " " << i;
      }
    }
  }
}

TEST(FastMac, SampleHasTheRatiosSizeAndIsFixedBySeed) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int n : {1, 7, 1000, 5000}) {
    std::vector<double> weight(static_cast<std::size_t>(n));
    for (auto& x : weight) x = u(rng) < 0.3 ? 0.0 : u(rng);  // zeros too
    for (double ratio : {0.01, 0.05, 0.1, 0.5, 1.0}) {
      const int k = fastmac::sample_size(n, ratio, 3);
      EXPECT_EQ(k, std::min(n, std::max(static_cast<int>(std::floor(ratio * n)), std::min(n, 3))));
      const auto a = fastmac::weighted_sample(weight, k, 42);
      ASSERT_EQ(static_cast<int>(a.size()), k);
      EXPECT_TRUE(std::is_sorted(a.begin(), a.end()));
      EXPECT_EQ(std::set<int>(a.begin(), a.end()).size(), a.size());
      EXPECT_EQ(fastmac::weighted_sample(weight, k, 42), a);  // same seed, same sample
      if (n >= 1000 && ratio < 0.5) {
        EXPECT_NE(fastmac::weighted_sample(weight, k, 43), a);
        // A zero weight is drawn only once every positive one is.
        for (int i : a) EXPECT_GT(weight[static_cast<std::size_t>(i)], 0.0);
      }
    }
  }
  EXPECT_EQ(fastmac::sample_size(1000, 0.1, 3), 100);
  EXPECT_EQ(fastmac::sample_size(5000, 0.05, 3), 250);
}

TEST(FastMac, InclusionProbabilitiesAreThoseOfSuccessiveWeightedDraws) {
  // Two draws without replacement, each proportional to weight: P(i) = p_i + sum_j p_j w_i /
  // (W - w_j). Frequencies over 40000 seeds within 0.01 of it.
  const std::vector<double> w{1.0, 2.0, 3.0, 4.0, 0.5};
  double total = 0.0;
  for (double x : w) total += x;
  std::vector<double> exact(w.size(), 0.0);
  for (std::size_t i = 0; i < w.size(); ++i) {
    exact[i] = w[i] / total;
    for (std::size_t j = 0; j < w.size(); ++j)
      if (j != i) exact[i] += w[j] / total * w[i] / (total - w[j]);
  }
  std::vector<double> freq(w.size(), 0.0);
  const int draws = 40000;
  for (int s = 0; s < draws; ++s)
    for (int i : fastmac::weighted_sample(w, 2, static_cast<std::uint64_t>(s) * 7919 + 1))
      freq[static_cast<std::size_t>(i)] += 1.0 / draws;
  for (std::size_t i = 0; i < w.size(); ++i) EXPECT_NEAR(freq[i], exact[i], 0.01) << i;
}

TEST(FastMac, NodeGuidedSelectionKeepsTheLargestCliqueThroughEachVertex) {
  // Oracle: every maximal clique by brute force over subsets; each vertex's largest one must be
  // among the kept cliques (same size, containing it), and each kept one is maximal.
  std::mt19937_64 rng(17);
  for (int trial = 0; trial < 30; ++trial) {
    const int n = 6 + trial % 10;
    BitGraph g = test::random_graph(n, 0.3 + 0.4 * (trial % 3) / 2.0, rng);
    std::vector<int> largest(static_cast<std::size_t>(n), 0);
    for (std::uint32_t mask = 1; mask < (1u << n); ++mask) {
      std::vector<int> s;
      for (int v = 0; v < n; ++v)
        if ((mask >> v) & 1) s.push_back(v);
      if (static_cast<int>(s.size()) < 3 || !g.is_clique(s)) continue;
      for (int v : s) largest[v] = std::max(largest[v], static_cast<int>(s.size()));
    }
    MaximalCliqueParams mp;
    mp.min_size = 3;
    const auto kept = fastmac::node_guided_cliques(g, mp);
    EXPECT_TRUE(kept.complete);
    std::vector<int> covered(static_cast<std::size_t>(n), 0);
    for (const auto& c : kept.cliques) {
      EXPECT_TRUE(g.is_clique(c));
      for (int v : c) covered[v] = std::max(covered[v], static_cast<int>(c.size()));
      for (int v = 0; v < n; ++v) {  // maximal: no vertex extends it
        if (std::find(c.begin(), c.end(), v) != c.end()) continue;
        bool extends = true;
        for (int u : c) extends = extends && g.adjacent(u, v);
        EXPECT_FALSE(extends) << trial;
      }
    }
    EXPECT_EQ(covered, largest) << trial;
  }
}

// ---------------------------------------------------------------------------------------------
// Both: recovery of drawn motions and threads (the solver contract runs in
// test_field_verifiers' EachSolver).

struct Regime {
  std::string solver;
  int dim;
  int n;
  double outliers;
  int metric = 0;
  std::string name;
};

class Recovers : public ::testing::TestWithParam<Regime> {};

template <int Dim>
void expect_recovery(const Regime& regime) {
  const auto solver = SolverRegistry::create(regime.solver);
  SolverParams params;
  params.turboreg.metric = regime.metric;
  double total_ms = 0.0;
  const int trials = 3;
  for (std::uint64_t seed = 1; seed <= trials; ++seed) {
    SyntheticParams p;
    p.n = regime.n;
    p.outlier_ratio = regime.outliers;
    p.seed = seed;
    const auto set = make_synthetic<Dim>(p);
    params.seed = seed;
    const auto start = std::chrono::steady_clock::now();
    const Result<Dim> r = solver->solve(set.corr, params);
    total_ms +=
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    ASSERT_EQ(r.status, Status::ok) << regime.name << " seed " << seed << ": " << r.message;
    EXPECT_LT(rotation_error_deg(r.T_target_source, *set.truth.T_target_source), 1.0) << seed;
    EXPECT_LT(translation_error(r.T_target_source, *set.truth.T_target_source), 0.1) << seed;
    const auto s = inlier_scores(r.inliers, set.truth.labels);
    EXPECT_GT(s.precision, 0.9) << seed;
    EXPECT_GT(s.recall, 0.8) << seed;
    EXPECT_TRUE(std::is_sorted(r.inliers.begin(), r.inliers.end()));
    EXPECT_EQ(std::adjacent_find(r.inliers.begin(), r.inliers.end()), r.inliers.end());
  }
  std::cout << "[ timing   ] " << regime.name << ": " << total_ms / trials << " ms per solve\n";
}

TEST_P(Recovers, DrawnMotion) {
  if (GetParam().dim == 2) {
    expect_recovery<2>(GetParam());
  } else {
    expect_recovery<3>(GetParam());
  }
}

Regime regime(std::string solver, int dim, int n, double outliers, int metric = 0) {
  Regime r{std::move(solver), dim, n, outliers, metric, ""};
  r.name = r.solver + "_" + std::to_string(dim) + "D_n" + std::to_string(n) + "_" +
           std::to_string(static_cast<int>(std::lround(outliers * 100))) + "pct";
  if (metric == 1) r.name += "_mae";
  if (metric == 2) r.name += "_mse";
  return r;
}

// TurboReg: 95% and 99% outliers at n = 1000 (its 3DLoMatch regime and beyond), every metric;
// FastMAC: n = 1000-5000 at 90-95% outliers (its KITTI and 3DMatch regimes).
INSTANTIATE_TEST_SUITE_P(
    Regimes, Recovers,
    ::testing::Values(regime("turboreg", 2, 1000, 0.95), regime("turboreg", 3, 1000, 0.95),
                      regime("turboreg", 2, 1000, 0.99), regime("turboreg", 3, 1000, 0.99),
                      regime("turboreg", 3, 1000, 0.95, 1), regime("turboreg", 3, 1000, 0.95, 2),
                      regime("fastmac", 2, 1000, 0.9), regime("fastmac", 3, 1000, 0.9),
                      regime("fastmac", 2, 1000, 0.95), regime("fastmac", 3, 1000, 0.95),
                      regime("fastmac", 2, 5000, 0.95), regime("fastmac", 3, 5000, 0.95)),
    [](const auto& info) { return info.param.name; });

class EachSolver : public ::testing::TestWithParam<std::string> {};

template <int Dim>
void expect_same_answer_for_one_and_two_threads(const std::string& name) {
  const auto solver = SolverRegistry::create(name);
  for (std::uint64_t seed = 1; seed <= 3; ++seed) {
    SyntheticParams p;
    p.n = 1500;
    p.outlier_ratio = 0.9;
    p.seed = seed;
    const auto set = make_synthetic<Dim>(p);
    SolverParams one, two;
    one.threads = 1;
    two.threads = 2;
    one.seed = two.seed = seed;
    const auto a = solver->solve(set.corr, one);
    const auto b = solver->solve(set.corr, two);
    ASSERT_EQ(a.status, Status::ok) << a.message;
    EXPECT_EQ(a.inliers, b.inliers);
    EXPECT_TRUE(a.T_target_source.matrix() == b.T_target_source.matrix());
    EXPECT_EQ(a.counters.iterations, b.counters.iterations);
    EXPECT_EQ(a.counters.branch_nodes, b.counters.branch_nodes);
  }
}

TEST_P(EachSolver, SameAnswerForOneAndTwoThreads) {
  expect_same_answer_for_one_and_two_threads<2>(GetParam());
  expect_same_answer_for_one_and_two_threads<3>(GetParam());
}

INSTANTIATE_TEST_SUITE_P(TurboRegFastMac, EachSolver, ::testing::Values("turboreg", "fastmac"));

}  // namespace
}  // namespace verifybench
