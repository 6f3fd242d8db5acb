// The correspondence graph against its definition, Eq. (1), evaluated pair by pair.
#include <gtest/gtest.h>

#include <atomic>
#include <stdexcept>

#include "core/parallel.hpp"
#include "generators/synthetic.hpp"
#include "graph/compatibility_graph.hpp"
#include "graph/small_graph.hpp"
#include "test_util.hpp"

namespace verifybench {
namespace {

template <int Dim>
void check_against_definition(std::uint64_t seed) {
  SyntheticParams p;
  p.n = 150;
  p.outlier_ratio = 0.6;
  p.seed = seed;
  const auto set = make_synthetic<Dim>(p);
  const double eps = 0.4;
  const BitGraph g = build_compatibility_graph(set.corr, GraphParams{eps});
  long long edges = 0;
  for (int i = 0; i < p.n; ++i) {
    EXPECT_FALSE(g.adjacent(i, i));
    for (int j = 0; j < p.n; ++j) {
      if (i == j) continue;
      const double dm = (set.corr.source.col(i) - set.corr.source.col(j)).norm();
      const double dq = (set.corr.target.col(i) - set.corr.target.col(j)).norm();
      ASSERT_EQ(g.adjacent(i, j), std::abs(dm - dq) < eps) << i << "," << j;
      edges += i < j && g.adjacent(i, j);
    }
  }
  EXPECT_EQ(g.edge_count(), edges);
}

// The pool behind every parallel stage: each index runs exactly once, in the block of its worker,
// for any count and thread count, over many jobs on one pool; an exception reaches the caller.
TEST(WorkerPool, EveryIndexOnceInFixedBlocksAndErrorsReachTheCaller) {
  for (int threads : {1, 2, 3, 5}) {
    WorkerPool pool(threads);
    ASSERT_EQ(pool.size(), threads);
    for (int count : {0, 1, 2, 7, 64, 1000}) {
      std::vector<std::atomic<int>> calls(static_cast<std::size_t>(count));
      std::vector<std::thread::id> who(static_cast<std::size_t>(count));
      pool.parallel_for(count, [&](int i) {
        ++calls[static_cast<std::size_t>(i)];
        who[static_cast<std::size_t>(i)] = std::this_thread::get_id();
      });
      for (int i = 0; i < count; ++i) EXPECT_EQ(calls[static_cast<std::size_t>(i)], 1) << i;
      // Block k of `threads` contiguous blocks is one worker's: ids change at most threads - 1
      // times.
      int changes = 0;
      for (int i = 1; i < count; ++i)
        changes += who[static_cast<std::size_t>(i)] != who[static_cast<std::size_t>(i - 1)];
      EXPECT_LE(changes, threads - 1) << threads << " threads, " << count;
    }
    EXPECT_THROW(pool.parallel_for(10,
                                   [](int i) {
                                     if (i == 7) throw std::runtime_error("seven");
                                   }),
                 std::runtime_error);
    std::atomic<int> after{0};
    pool.parallel_for(10, [&](int) { ++after; });  // still usable after an error
    EXPECT_EQ(after, 10);
  }
  EXPECT_EQ(resolve_threads(3), 3);
  EXPECT_GE(resolve_threads(0), 1);
}

TEST(CompatibilityGraph, MatchesDefinition2D) { check_against_definition<2>(1); }
TEST(CompatibilityGraph, MatchesDefinition3D) { check_against_definition<3>(2); }

TEST(CompatibilityGraph, SameGraphForAnySizeAndThreadCount) {
  // Sizes around word boundaries; every thread count must give the bit-identical graph, which must
  // match Eq. (1) evaluated pair by pair.
  for (int n : {1, 2, 63, 64, 65, 127, 128, 129, 300, 700}) {
    SyntheticParams p;
    p.n = n;
    p.outlier_ratio = 0.7;
    p.seed = static_cast<std::uint64_t>(n);
    const auto set = make_synthetic<3>(p);
    const BitGraph one =
        build_compatibility_graph(set.corr, GraphParams{0.5, std::size_t{1} << 30, 1});
    for (int threads : {2, 3, 0}) {
      const BitGraph many =
          build_compatibility_graph(set.corr, GraphParams{0.5, std::size_t{1} << 30, threads});
      for (int i = 0; i < n; ++i)
        for (int w = 0; w < one.words(); ++w)
          ASSERT_EQ(one.row(i)[w], many.row(i)[w]) << n << " " << threads;
    }
    for (int i = 0; i < n; ++i) {
      for (int j = 0; j < n; ++j) {
        const double dm = (set.corr.source.col(i) - set.corr.source.col(j)).norm();
        const double dq = (set.corr.target.col(i) - set.corr.target.col(j)).norm();
        ASSERT_EQ(one.adjacent(i, j), i != j && std::abs(dm - dq) < 0.5)
            << n << ": " << i << "," << j;
      }
    }
  }
}

TEST(CompatibilityGraph, PairsExactlyAtEpsAreDecidedAsInDouble) {
  // The kernel runs in float and re-decides pairs near eps in double: choose eps equal to a pair's
  // own length difference (strictly-less fails) and one ulp above (passes), far from the origin.
  SyntheticParams p;
  p.n = 200;
  p.outlier_ratio = 0.5;
  p.extent = 500.0;
  auto set = make_synthetic<3>(p);
  set.corr.source.array() += 3000.0;  // large coordinates stress float precision
  for (int trial = 0; trial < 20; ++trial) {
    const int i = (trial * 37) % p.n, j = (trial * 91 + 5) % p.n;
    if (i == j) continue;
    const double diff = std::abs((set.corr.source.col(i) - set.corr.source.col(j)).norm() -
                                 (set.corr.target.col(i) - set.corr.target.col(j)).norm());
    if (diff <= 0.0) continue;
    for (double eps : {diff, std::nextafter(diff, 1e300)}) {
      const BitGraph g = build_compatibility_graph(set.corr, GraphParams{eps});
      ASSERT_EQ(g.adjacent(i, j), diff < eps) << "pair " << i << "," << j << " eps " << eps;
      for (int a = 0; a < p.n; ++a) {
        for (int b = a + 1; b < p.n; ++b) {
          const double dm = (set.corr.source.col(a) - set.corr.source.col(b)).norm();
          const double dq = (set.corr.target.col(a) - set.corr.target.col(b)).norm();
          ASSERT_EQ(g.adjacent(a, b), std::abs(dm - dq) < eps) << a << "," << b;
        }
      }
    }
  }
}

TEST(CompatibilityGraph, NoiselessInliersFormAClique) {
  SyntheticParams p;
  p.n = 200;
  p.outlier_ratio = 0.8;
  p.noise = 0.0;
  const auto set = make_synthetic<3>(p);
  const BitGraph g = build_compatibility_graph(set.corr, GraphParams{1e-6});
  std::vector<int> inliers;
  for (int i = 0; i < p.n; ++i)
    if (set.truth.labels[i]) inliers.push_back(i);
  EXPECT_EQ(inliers.size(), 40u);
  EXPECT_TRUE(g.is_clique(inliers));
}

TEST(CompatibilityGraph, RefusesGraphsOverTheMemoryCap) {
  Correspondences<3> c;
  c.source = Eigen::Matrix3Xd::Zero(3, 5000);
  c.target = c.source;
  GraphParams p;
  p.max_bytes = 1 << 20;  // 5000 vertices need about 3 MiB
  try {
    build_compatibility_graph(c, p);
    FAIL() << "expected std::length_error";
  } catch (const std::length_error& e) {
    EXPECT_NE(std::string(e.what()).find("5000 vertices"), std::string::npos) << e.what();
  }
  EXPECT_EQ(BitGraph::bytes_for(5000), 5000u * 79u * 8u);
}

TEST(CompatibilityGraph, RejectsNonPositiveEps) {
  Correspondences<2> c;
  c.source = Eigen::Matrix2Xd::Zero(2, 3);
  c.target = c.source;
  EXPECT_THROW(build_compatibility_graph(c, GraphParams{0.0}), std::invalid_argument);
  EXPECT_THROW(build_compatibility_graph(c, GraphParams{-1.0}), std::invalid_argument);
}

/// Eq. (1) for one pair, as the tests above evaluate it.
template <int Dim>
bool definition(const Correspondences<Dim>& c, int i, int j, double eps) {
  return std::abs((c.source.col(i) - c.source.col(j)).norm() -
                  (c.target.col(i) - c.target.col(j)).norm()) < eps;
}

template <int Dim>
void check_small_graphs_against_definition(std::uint64_t seed) {
  // Every part size the screen uses, strided as clique_number_bound strides them, far from the
  // origin; and eps at a pair's own gap (strictly-less fails) and one ulp above (passes).
  SyntheticParams p;
  p.n = 300;
  p.outlier_ratio = 0.6;
  p.extent = 500.0;
  p.seed = seed;
  auto set = make_synthetic<Dim>(p);
  set.corr.source.array() += 3000.0;
  std::vector<double> eps_values = {0.4, 2.0};
  for (int k = 0; k < 6; ++k) {
    const double gap = std::abs((set.corr.source.col(k) - set.corr.source.col(k + 7)).norm() -
                                (set.corr.target.col(k) - set.corr.target.col(k + 7)).norm());
    eps_values.push_back(gap);
    eps_values.push_back(std::nextafter(gap, 1e300));
  }
  for (int size : {1, 2, 5, 8, 16, 63, 64}) {
    const int parts = (p.n + size - 1) / size;
    for (int q = 0; q < std::min(parts, 8); ++q) {
      int index[64], count = 0;
      for (int i = q; i < p.n && count < size; i += parts) index[count++] = i;
      for (int k = 0; k < 6 && size == 8 && q == 0; ++k) {  // the pairs at eps in one part
        index[2 * (k % 4)] = k;
        index[2 * (k % 4) + 1] = k + 7;
      }
      for (double eps : eps_values) {
        const SmallGraph g = small_compatibility_graph(set.corr, index, count, eps);
        ASSERT_EQ(g.n, count);
        for (int a = 0; a < count; ++a) {
          EXPECT_FALSE((g.row[a] >> a) & 1);
          for (int b = 0; b < count; ++b) {
            if (a == b) continue;
            ASSERT_EQ((g.row[a] >> b) & 1,
                      definition(set.corr, index[a], index[b], eps) ? 1u : 0u)
                << "size " << size << " eps " << eps << " pair " << index[a] << "," << index[b];
          }
        }
      }
    }
  }
  int index[65] = {};
  EXPECT_THROW(small_compatibility_graph(set.corr, index, 65, 0.4), std::invalid_argument);
}

TEST(SmallGraph, MatchesDefinition2D) { check_small_graphs_against_definition<2>(3); }
TEST(SmallGraph, MatchesDefinition3D) { check_small_graphs_against_definition<3>(4); }

SmallGraph to_small(const BitGraph& g) {
  SmallGraph s;
  s.n = g.size();
  for (int v = 0; v < g.size(); ++v) s.row[v] = g.row(v)[0];
  return s;
}

TEST(SmallGraph, CliqueNumberMatchesBruteForceAndPlantedCliques) {
  // Oracles: exhaustive search up to 24 vertices at every density; at 64 vertices a planted
  // clique of 20 in a sparse graph (whose own cliques stay far below 20), and the extremes.
  std::mt19937_64 rng(11);
  for (int n : {0, 1, 2, 7, 16, 24}) {
    for (double density : {0.05, 0.3, 0.6, 0.9}) {
      for (int rep = 0; rep < 5; ++rep) {
        const BitGraph g = test::random_graph(n, density, rng);
        EXPECT_EQ(small_clique_number(to_small(g)), test::brute_force_clique_number(g))
            << n << " " << density << " " << rep;
      }
    }
  }
  for (int rep = 0; rep < 10; ++rep) {
    BitGraph g = test::random_graph(64, 0.1, rng);
    test::plant_clique(g, 20, rng);
    EXPECT_EQ(small_clique_number(to_small(g)), 20) << rep;
  }
  BitGraph complete(64), empty(64);
  for (int u = 0; u < 64; ++u)
    for (int v = u + 1; v < 64; ++v) complete.add_edge(u, v);
  EXPECT_EQ(small_clique_number(to_small(complete)), 64);
  EXPECT_EQ(small_clique_number(to_small(empty)), 1);
}

}  // namespace
}  // namespace verifybench
