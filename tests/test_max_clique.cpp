// Every registered maximum clique algorithm against a brute-force oracle, and the anytime limits.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <set>

#include "clique_oracles.hpp"
#include "cliques/detail/bbmc.hpp"
#include "cliques/max_clique.hpp"
#include "graph/compatibility_graph.hpp"
#include "graph/planted.hpp"
#include "test_util.hpp"

namespace verifybench {
namespace {

std::vector<std::string> exact_algorithms() {
  register_clique_algorithms();
  std::vector<std::string> names;
  for (const auto& info : CliqueAlgorithms::list())
    if (info.exact) names.push_back(info.name);
  return names;
}

CliqueSearchResult solve(const std::string& algorithm, const BitGraph& g,
                         CliqueSearchParams p = {}) {
  return CliqueAlgorithms::get(algorithm).run(g, p);
}

class Exact : public ::testing::TestWithParam<std::string> {};

TEST_P(Exact, MatchesBruteForceOnRandomGraphs) {
  std::mt19937_64 rng(20251122);
  int graphs = 0;
  for (int n = 1; n <= 24; ++n) {
    for (double density : {0.1, 0.3, 0.5, 0.7, 0.85, 0.95}) {
      for (int rep = 0; rep < 3; ++rep, ++graphs) {
        const BitGraph g = test::random_graph(n, density, rng);
        const CliqueSearchResult r = solve(GetParam(), g);
        ASSERT_TRUE(r.optimal);
        ASSERT_FALSE(r.stopped);
        ASSERT_TRUE(g.is_clique(r.clique)) << "n=" << n << " density=" << density;
        ASSERT_EQ(static_cast<int>(r.clique.size()), test::brute_force_clique_number(g))
            << "n=" << n << " density=" << density << " rep=" << rep;
        ASSERT_TRUE(std::is_sorted(r.clique.begin(), r.clique.end()));
        ASSERT_LE(static_cast<int>(r.clique.size()), r.upper_bound);
      }
    }
  }
  EXPECT_EQ(graphs, 24 * 6 * 3);
}

TEST_P(Exact, EdgeCaseGraphs) {
  EXPECT_EQ(solve(GetParam(), BitGraph(10)).clique.size(), 1u);  // no edges
  EXPECT_TRUE(solve(GetParam(), BitGraph(0)).clique.empty());    // no vertices
  for (int n : {1, 2, 63, 64, 65, 130}) {                        // complete graphs
    BitGraph g(n);
    for (int u = 0; u < n; ++u)
      for (int v = u + 1; v < n; ++v) g.add_edge(u, v);
    EXPECT_EQ(static_cast<int>(solve(GetParam(), g).clique.size()), n) << n;
  }
}

TEST_P(Exact, FindsPlantedCliqueAcrossWordBoundaries) {
  std::mt19937_64 rng(7);
  BitGraph g = test::random_graph(300, 0.1, rng);
  const std::vector<int> planted = test::plant_clique(g, 25, rng);
  const auto r = solve(GetParam(), g);
  EXPECT_TRUE(r.optimal);
  // G(300, 0.1) alone has clique number far below 25, so the planted clique is the unique maximum.
  EXPECT_EQ(r.clique, planted);
}

TEST_P(Exact, FindsPlantedCliqueInLongSparseRows) {
  // 2100 vertices (33 words a row) at density 0.1: subtrees below the root are searched on packed
  // subgraphs (bbmc.hpp, search_packed). G(2100, 0.1) has clique number ~6, so the planted 14 is
  // the unique maximum.
  std::mt19937_64 rng(53);
  BitGraph g = test::random_graph(2100, 0.1, rng);
  const std::vector<int> planted = test::plant_clique(g, 14, rng);
  CliqueSearchParams p;
  p.time_limit_s = 120;  // a safety net against a hang, not a timing assertion
  const auto r = solve(GetParam(), g, p);
  EXPECT_TRUE(r.optimal);
  EXPECT_EQ(r.clique, planted);
}

TEST_P(Exact, PermutingVerticesKeepsTheCliqueNumber) {
  std::mt19937_64 rng(11);
  for (int rep = 0; rep < 10; ++rep) {
    const BitGraph g = test::random_graph(60, 0.6, rng);
    std::vector<int> perm(60);
    std::iota(perm.begin(), perm.end(), 0);
    std::shuffle(perm.begin(), perm.end(), rng);
    BitGraph h(60);
    for (int u = 0; u < 60; ++u)
      for (int v = u + 1; v < 60; ++v)
        if (g.adjacent(u, v)) h.add_edge(perm[u], perm[v]);
    EXPECT_EQ(solve(GetParam(), g).clique.size(), solve(GetParam(), h).clique.size());
  }
}

TEST_P(Exact, TimeLimitReturnsBestSoFarWithStatus) {
  std::mt19937_64 rng(5);
  const BitGraph g = test::random_graph(400, 0.9, rng);  // minutes to prove optimal for any of them
  CliqueSearchParams p;
  p.time_limit_s = 0.05;
  const auto r = solve(GetParam(), g, p);
  EXPECT_TRUE(r.stopped);
  EXPECT_FALSE(r.optimal);
  EXPECT_TRUE(g.is_clique(r.clique));
}

// A limit already past when the search is called: the set-up (core numbers, orders, relabelling;
// a few hundred ms at n = 20,000) gives up before any branch node, with status time_limit.
TEST_P(Exact, PassedDeadlineStopsBeforeTheSearch) {
  std::mt19937_64 rng(7);
  const BitGraph g = test::random_graph(2000, 0.5, rng);
  CliqueSearchParams p;
  p.time_limit_s = 0;
  const auto r = solve(GetParam(), g, p);
  EXPECT_TRUE(r.stopped);
  EXPECT_FALSE(r.optimal);
  EXPECT_EQ(r.nodes, 0);
  EXPECT_TRUE(g.is_clique(r.clique));
}

TEST_P(Exact, SmallNearCliquesMatchTheirBlockOracle) {
  // 40-70 vertices: the cover search (reductions, LP bound, packing) and the hand-off run here.
  for (int rep = 0; rep < 6; ++rep) {
    const PlantedGraph nc =
        block_near_clique(40 + 5 * rep, 10 + rep, 8 + 3 * rep, 0.1 + 0.12 * rep, rep);
    const CliqueSearchResult r = solve(GetParam(), nc.g);
    ASSERT_TRUE(nc.g.is_clique(r.clique)) << rep;
    EXPECT_EQ(static_cast<int>(r.clique.size()), nc.omega) << rep;
    EXPECT_TRUE(r.optimal) << rep;
  }
}

// Correspondence graphs shaped like the corpus's k-NN dumps, small enough for brute force: source
// keypoints on a voxel grid (V = 0.5 m), each matched to k targets as FPFH k-NN matching does: its
// true image (when it is an inlier), targets one voxel beside it (similar descriptors of
// neighbouring voxels, compatible with each other at eps = 2V) and a far random target.
Correspondences<3> knn_like_set(int keypoints, int k, double inliers, std::mt19937_64& rng) {
  const double V = 0.5;
  std::uniform_int_distribution<int> cell(-6, 6), kind(0, 2);
  std::uniform_real_distribution<double> far(-20.0, 20.0), noise(-0.1, 0.1);
  std::bernoulli_distribution inlier(inliers);
  const Rigid<3> T = test::random_rigid<3>(rng);
  Correspondences<3> c;
  c.source.resize(3, keypoints * k);
  c.target.resize(3, keypoints * k);
  for (int p = 0; p < keypoints; ++p) {
    const Eigen::Vector3d m(V * cell(rng), V * cell(rng), V * cell(rng));
    const Eigen::Vector3d image = T * m;
    const bool correct = inlier(rng);
    for (int j = 0; j < k; ++j) {
      Eigen::Vector3d q = Eigen::Vector3d(far(rng), far(rng), far(rng));
      const int what = j == 0 ? (correct ? 0 : 2) : kind(rng);
      if (what == 0) q = image + Eigen::Vector3d(noise(rng), noise(rng), noise(rng));
      if (what == 1) q = image + V * Eigen::Vector3d(cell(rng) % 2, cell(rng) % 2, 1.0);
      c.source.col(p * k + j) = m;
      c.target.col(p * k + j) = q;
    }
  }
  return c;
}

TEST_P(Exact, SmallKnnLikeCorrespondenceGraphsMatchBruteForce) {
  std::mt19937_64 rng(20261202);
  GraphParams gp;
  gp.eps = 1.0;  // 2V
  int graphs = 0, nontrivial = 0;
  struct Shape {
    int keypoints, k;
  };
  for (const Shape s : {Shape{22, 1}, Shape{12, 2}, Shape{8, 3}, Shape{6, 4}, Shape{2, 10}}) {
    for (double inliers : {0.3, 0.7, 1.0}) {
      for (int rep = 0; rep < 4; ++rep, ++graphs) {
        const BitGraph g =
            build_compatibility_graph<3>(knn_like_set(s.keypoints, s.k, inliers, rng), gp);
        const CliqueSearchResult r = solve(GetParam(), g);
        const int omega = test::brute_force_clique_number(g);
        nontrivial += omega >= 4;
        ASSERT_TRUE(r.optimal);
        ASSERT_TRUE(g.is_clique(r.clique)) << s.keypoints << "x" << s.k << " rep " << rep;
        ASSERT_EQ(static_cast<int>(r.clique.size()), omega)
            << s.keypoints << "x" << s.k << " inliers " << inliers << " rep " << rep;
        ASSERT_LE(omega, r.upper_bound);
      }
    }
  }
  EXPECT_EQ(graphs, 5 * 3 * 4);
  EXPECT_GE(nontrivial, graphs / 2);  // the sets are not all chance pairs
}

INSTANTIATE_TEST_SUITE_P(Algorithms, Exact, ::testing::ValuesIn(exact_algorithms()),
                         [](const auto& info) {
                           std::string name = info.param;
                           std::replace(name.begin(), name.end(), '-', '_');
                           return name;
                         });

TEST(MaxClique, LargePlantedCliqueIsProvedOptimal) {
  // Half the inliers of a big correspondence set form one clique: the search must not descend
  // vertex by vertex through it (each of our algorithms detects a candidate set that is a clique).
  register_clique_algorithms();
  std::mt19937_64 rng(29);
  BitGraph g = test::random_graph(1200, 0.05, rng);
  const std::vector<int> planted = test::plant_clique(g, 600, rng);
  for (const char* algorithm : {"bbmc", "bbmc-kcore", "bbmc-dec"}) {
    CliqueSearchParams p;
    p.time_limit_s = 120;  // a safety net against a hang, not a timing assertion
    const auto r = CliqueAlgorithms::get(algorithm).run(g, p);
    EXPECT_TRUE(r.optimal) << algorithm;
    EXPECT_EQ(r.clique, planted) << algorithm;
  }
}

/// `algorithm` returns a maximum clique of the planted graph, proved, with the bound at omega.
void expect_proves(const std::string& algorithm, const PlantedGraph& nc, int k) {
  CliqueSearchParams p;
  p.time_limit_s = 120;  // a safety net against a hang, not a timing assertion
  const auto r = CliqueAlgorithms::get(algorithm).run(nc.g, p);
  EXPECT_TRUE(nc.g.is_clique(r.clique)) << algorithm << " k=" << k;
  EXPECT_EQ(static_cast<int>(r.clique.size()), nc.omega) << algorithm << " k=" << k;
  EXPECT_TRUE(r.optimal) << algorithm << " k=" << k;
  EXPECT_EQ(r.upper_bound, nc.omega) << algorithm << " k=" << k;
}

TEST(MaxClique, LargeNearCliquesAreProvedByTheCoverSearch) {
  // Cliques of 500-3000 with edges removed in blocks (0.5% at 500, 0.2% at 1000, 0.08% at 3000:
  // blocks of 24 cap the share), plus outliers: omega is 60-80% of K, the regime of FPFH
  // correspondence graphs after pruning, where colouring bounds fail.
  register_clique_algorithms();
  struct Case {
    int k, outliers;
    double density;
  };
  for (const Case c : {Case{500, 500, 0.1}, Case{1000, 1000, 0.1}, Case{3000, 1500, 0.1}}) {
    const PlantedGraph nc = block_near_clique(c.k, c.outliers, 24, c.density, 7 + c.k);
    EXPECT_GT(nc.removed, 0.0) << c.k;
    EXPECT_GE(nc.omega, c.k / 2) << c.k;
    for (const char* algorithm : {"cover", "auto", kDefaultCliqueAlgorithm})
      expect_proves(algorithm, nc, c.k);
  }
}

TEST(MaxClique, NearCliquesWithOneToFivePercentRemovedMatchTheirHubOracle) {
  // Issue #12, item 7: cliques of 500-3000 with 1-5% of their pairs removed, plus outliers.
  register_clique_algorithms();
  struct Case {
    int k, hubs, outliers;
    double min_removed, max_removed;
  };
  for (const Case c : {Case{500, 50, 500, 0.03, 0.05}, Case{1000, 70, 1000, 0.02, 0.04},
                       Case{3000, 70, 1500, 0.008, 0.015}}) {
    const PlantedGraph nc = hub_near_clique(c.k, c.hubs, c.outliers, 12 + c.k);
    EXPECT_GE(nc.removed, c.min_removed) << c.k;
    EXPECT_LE(nc.removed, c.max_removed) << c.k;
    EXPECT_GE(nc.omega, 2 * c.k / 5) << c.k;
    // The colouring searches prove K = 500 (0.05-0.6 s) and stop at a 20 s limit from K = 1000 on
    // (BENCHMARK.md section 19): here only where they finish.
    std::vector<std::string> algorithms{"cover", "auto", kDefaultCliqueAlgorithm};
    if (c.k == 500) {
      for (const char* a : {"bbmc", "bbmcr", "bbmcx", "bbmcx-ls", "bbmc-kcore", "bbmc-dec"})
        algorithms.emplace_back(a);
    }
    for (const std::string& algorithm : algorithms) expect_proves(algorithm, nc, c.k);
  }
}

TEST(PlantedGraph, RefusesParametersItsOracleCannotHandle) {
  EXPECT_THROW(block_near_clique(0, 10, 8, 0.1, 1), std::invalid_argument);
  EXPECT_THROW(block_near_clique(50, -1, 8, 0.1, 1), std::invalid_argument);
  EXPECT_THROW(block_near_clique(50, 10, 0, 0.1, 1), std::invalid_argument);  // would never end
  EXPECT_THROW(block_near_clique(50, 10, 33, 0.1, 1), std::invalid_argument);
  EXPECT_THROW(block_near_clique(50, 10, 8, 1.5, 1), std::invalid_argument);
  EXPECT_THROW(hub_near_clique(50, 51, 10, 1), std::invalid_argument);
  EXPECT_THROW(hub_near_clique(500, 101, 10, 1), std::invalid_argument);
  EXPECT_THROW(hub_near_clique(50, -1, 10, 1), std::invalid_argument);
  EXPECT_EQ(block_near_clique(50, 0, 32, 0.0, 1).omega, 50);  // nothing removed: K itself
  EXPECT_EQ(hub_near_clique(60, 0, 0, 1).g.size(), 60);
}

TEST(MaxClique, DecompositionGivesTheSameCliqueForAnyThreadCount) {
  // Random graphs have many maximum cliques; the parallel search must still return the same one.
  register_clique_algorithms();
  std::mt19937_64 rng(41);
  for (int rep = 0; rep < 12; ++rep) {
    const BitGraph g = test::random_graph(200 + 10 * rep, 0.4 + 0.05 * (rep % 3), rng);
    CliqueSearchParams p;
    p.threads = 1;
    const auto one = CliqueAlgorithms::get("bbmc-dec").run(g, p);
    ASSERT_TRUE(one.optimal);
    ASSERT_TRUE(g.is_clique(one.clique));
    EXPECT_EQ(one.clique.size(), CliqueAlgorithms::get("bbmc").run(g, {}).clique.size());
    for (int threads : {2, 3, 8}) {
      p.threads = threads;
      const auto many = CliqueAlgorithms::get("bbmc-dec").run(g, p);
      ASSERT_TRUE(many.optimal);
      ASSERT_EQ(many.clique, one.clique) << "rep " << rep << " threads " << threads;
    }
  }
}

TEST(MaxClique, NodeLimitReturnsBestSoFarWithStatus) {
  std::mt19937_64 rng(3);
  const BitGraph g = test::random_graph(200, 0.9, rng);  // far too hard for 50 nodes
  CliqueSearchParams p;
  p.node_limit = 50;
  const auto r = max_clique(g, p);
  EXPECT_TRUE(r.stopped);
  EXPECT_LE(r.nodes, 50);
  EXPECT_TRUE(g.is_clique(r.clique));
  EXPECT_GE(r.clique.size(), 2u);  // the greedy incumbent is kept
}

TEST(LocalSearch, FindsTheCliqueNumberOfSmallGraphs) {
  std::mt19937_64 rng(31);
  for (int rep = 0; rep < 150; ++rep) {
    const int n = 8 + rep % 15;
    const BitGraph g = test::random_graph(n, 0.3 + 0.1 * (rep % 7), rng);
    LocalSearchParams p;
    p.max_steps = 5000;
    p.seed = static_cast<std::uint64_t>(rep);
    const std::vector<int> c = local_search_clique(g, p);
    ASSERT_TRUE(g.is_clique(c)) << "rep " << rep;
    ASSERT_TRUE(std::is_sorted(c.begin(), c.end()));
    ASSERT_EQ(static_cast<int>(c.size()), test::brute_force_clique_number(g)) << "rep " << rep;
  }
}

TEST(LocalSearch, FindsACliqueHiddenAmongLowDegreeVertices) {
  // brock-style: 30 vertices of a 240-vertex graph form a clique but see the rest with
  // probability 0.5, while the rest see each other with 0.75 (clique number ~ 21 there), so a
  // greedy by degree or core number starts elsewhere.
  std::mt19937_64 rng(43);
  const int n = 240, k = 30;
  BitGraph g(n);
  std::bernoulli_distribution dense(0.75), sparse(0.5);
  for (int u = 0; u < n; ++u) {
    for (int v = u + 1; v < n; ++v) {
      if (v < k || (u >= k ? dense(rng) : sparse(rng))) g.add_edge(u, v);
    }
  }
  std::vector<int> hidden(k);
  std::iota(hidden.begin(), hidden.end(), 0);
  register_clique_algorithms();
  EXPECT_LT(solve("greedy", g).clique.size(), hidden.size());
  LocalSearchParams p;
  p.max_steps = 200000;
  p.target = k;
  long long steps = 0;
  EXPECT_EQ(local_search_clique(g, p, &steps), hidden);
  EXPECT_LT(steps, p.max_steps);
  // Exact with the local search interleaved: the hidden clique, proved maximum.
  const auto r = solve("bbmcx-ls", g);
  EXPECT_TRUE(r.optimal);
  EXPECT_EQ(r.clique, hidden);
  EXPECT_GT(r.local_search_steps, 0);
}

TEST(LocalSearch, SameSeedSameClimbAndTargetStopsIt) {
  std::mt19937_64 rng(37);
  const BitGraph g = test::random_graph(200, 0.8, rng);
  LocalSearchParams p;
  p.max_steps = 20000;
  p.seed = 9;
  long long steps_a = 0, steps_b = 0;
  const auto a = local_search_clique(g, p, &steps_a);
  const auto b = local_search_clique(g, p, &steps_b);
  EXPECT_EQ(a, b);
  EXPECT_EQ(steps_a, steps_b);
  EXPECT_GE(steps_a, p.max_steps);  // no target: it uses its whole budget
  p.target = 5;
  const auto c = local_search_clique(g, p, &steps_b);
  EXPECT_GE(c.size(), 5u);
  EXPECT_TRUE(g.is_clique(c));
  EXPECT_LT(steps_b, 100);  // a first descent in a dense graph passes 5 at once
  EXPECT_TRUE(local_search_clique(BitGraph(0), p).empty());
  // The step budget holds inside a descent too (a planted clique of thousands is one descent).
  BitGraph complete(300);
  for (int u = 0; u < 300; ++u)
    for (int v = u + 1; v < 300; ++v) complete.add_edge(u, v);
  LocalSearchParams few;
  few.max_steps = 10;
  const auto part = local_search_clique(complete, few, &steps_a);
  EXPECT_LE(steps_a, 10);
  EXPECT_TRUE(complete.is_clique(part));
  EXPECT_LE(part.size(), 11u);
}

TEST(MaxClique, InterleavedLocalSearchKeepsTheSearchExactMidTree) {
  // Graphs that take thousands of nodes, so the local search is consulted inside the tree and
  // can raise the incumbent there: the clique number must still be bbmc's, for any seed.
  register_clique_algorithms();
  std::mt19937_64 rng(47);
  for (int rep = 0; rep < 4; ++rep) {
    const BitGraph g = test::random_graph(150, 0.75 + 0.03 * rep, rng);
    const auto reference = solve("bbmc", g);
    ASSERT_TRUE(reference.optimal);
    for (std::uint64_t seed : {1u, 2u, 3u}) {
      CliqueSearchParams p;
      p.seed = seed;
      const auto r = solve("bbmcx-ls", g, p);
      ASSERT_TRUE(r.optimal);
      ASSERT_TRUE(g.is_clique(r.clique));
      EXPECT_EQ(r.clique.size(), reference.clique.size()) << "rep " << rep << " seed " << seed;
      EXPECT_GT(r.nodes, 2048) << "rep " << rep;  // the test exercises the consultations
    }
  }
  // Rows of 32 words: the subtrees run on packed subgraphs, which consult the local search too.
  const BitGraph g = test::random_graph(2000, 0.15, rng);
  const auto reference = solve("bbmc", g);
  const auto r = solve("bbmcx-ls", g);
  ASSERT_TRUE(reference.optimal && r.optimal);
  EXPECT_TRUE(g.is_clique(r.clique));
  EXPECT_EQ(r.clique.size(), reference.clique.size());
  EXPECT_GT(r.nodes, 20000);
}

TEST(MaxClique, GreedyIsAValidCliqueNoLargerThanOptimal) {
  register_clique_algorithms();
  std::mt19937_64 rng(23);
  int below = 0;
  for (int rep = 0; rep < 200; ++rep) {
    const BitGraph g = test::random_graph(22, 0.6, rng);
    const auto r = solve("greedy", g);
    const int omega = test::brute_force_clique_number(g);
    ASSERT_TRUE(g.is_clique(r.clique));
    ASSERT_LE(static_cast<int>(r.clique.size()), omega);
    below += static_cast<int>(r.clique.size()) < omega;
    if (r.optimal) {
      ASSERT_EQ(static_cast<int>(r.clique.size()), omega);  // only when bound-certified
    }
  }
  EXPECT_GT(below, 0);  // a heuristic: the graphs exercise clique sizes under omega too
  EXPECT_FALSE(CliqueAlgorithms::get("greedy").exact);
  EXPECT_THROW(CliqueAlgorithms::get("nope"), std::invalid_argument);
}

// The greedy clique as documented, written plainly: starts in decreasing core order (skipping
// those whose core cannot beat the best), each step the candidate of highest core, lowest id first.
std::vector<int> reference_greedy(const BitGraph& g, const CoreDecomposition& cd, int max_starts) {
  std::vector<int> best;
  int starts = 0;
  for (auto it = cd.order.rbegin(); it != cd.order.rend(); ++it) {
    if (cd.core[std::size_t(*it)] + 1 <= static_cast<int>(best.size())) continue;
    if (starts++ == max_starts) break;
    std::vector<int> clique{*it};
    for (;;) {
      int pick = -1;
      for (int u = 0; u < g.size(); ++u) {
        bool fits = true;
        for (int c : clique) fits = fits && g.adjacent(c, u);
        if (fits && (pick < 0 || cd.core[std::size_t(u)] > cd.core[std::size_t(pick)])) pick = u;
      }
      if (pick < 0) break;
      clique.push_back(pick);
    }
    if (clique.size() > best.size()) best = clique;
  }
  return best;
}

TEST(MaxClique, GreedyCliqueFollowsItsDefinition) {
  std::mt19937_64 rng(31);
  for (int rep = 0; rep < 40; ++rep) {
    // Densities on both sides of the greedy's switch (starts that see 1/8 of the vertices).
    const double density = rep % 3 == 0 ? 0.05 : rep % 3 == 1 ? 0.2 : 0.7;
    BitGraph g = test::random_graph(60 + 7 * rep, density, rng);
    if (rep % 4 == 0) test::plant_clique(g, 20, rng);
    const CoreDecomposition cd = core_decomposition(g);
    for (int starts : {1, 8, std::numeric_limits<int>::max()}) {
      bool stopped = false;
      EXPECT_EQ(detail::greedy_clique(g, cd, detail::kNoDeadline, stopped, starts),
                reference_greedy(g, cd, starts))
          << "rep " << rep << " starts " << starts;
      EXPECT_FALSE(stopped);
    }
  }
  const PlantedGraph nc = hub_near_clique(500, 50, 500, 512);  // a near-clique
  const CoreDecomposition cd = core_decomposition(nc.g);
  bool stopped = false;
  EXPECT_EQ(detail::greedy_clique(nc.g, cd, detail::kNoDeadline, stopped, 8),
            reference_greedy(nc.g, cd, 8));
}

std::set<std::vector<int>> brute_force_maximal_cliques(const BitGraph& g, int min_size) {
  std::set<std::vector<int>> out;
  const int n = g.size();
  for (std::uint32_t s = 1; s < (1u << n); ++s) {
    std::vector<int> c;
    for (int v = 0; v < n; ++v)
      if (s >> v & 1) c.push_back(v);
    if (static_cast<int>(c.size()) < min_size || !g.is_clique(c)) continue;
    bool maximal = true;
    for (int u = 0; u < n && maximal; ++u) {
      if (s >> u & 1) continue;
      bool all = true;
      for (int v : c) all = all && g.adjacent(u, v);
      maximal = !all;
    }
    if (maximal) out.insert(c);
  }
  return out;
}

TEST(MaximalCliques, MatchBruteForceEnumeration) {
  std::mt19937_64 rng(31);
  for (int rep = 0; rep < 120; ++rep) {
    const int n = 1 + rep % 14;
    const int min_size = 1 + rep % 4;
    const BitGraph g = test::random_graph(n, 0.2 + 0.6 * (rep % 7) / 6.0, rng);
    std::set<std::vector<int>> found;
    int reports = 0;
    MaximalCliqueParams p;
    p.min_size = min_size;
    const bool complete = for_each_maximal_clique(g, p, [&](const std::vector<int>& c) {
      std::vector<int> sorted = c;
      std::sort(sorted.begin(), sorted.end());
      found.insert(sorted);
      ++reports;
    });
    EXPECT_TRUE(complete);
    EXPECT_EQ(reports, static_cast<int>(found.size())) << "a clique was reported twice";
    ASSERT_EQ(found, brute_force_maximal_cliques(g, min_size)) << "n=" << n << " rep=" << rep;
  }
}

TEST(MaximalCliques, CapStopsTheEnumeration) {
  std::mt19937_64 rng(37);
  const BitGraph g = test::random_graph(60, 0.5, rng);
  MaximalCliqueParams p;
  p.max_cliques = 10;
  int reports = 0;
  EXPECT_FALSE(for_each_maximal_clique(g, p, [&](const std::vector<int>&) { ++reports; }));
  EXPECT_EQ(reports, 10);
}

// Relabelling scatters bits on sparse rows, transposes 64 x 64 blocks on dense ones and clears the
// non-edges on near-complete ones: each must keep every pair, for whole-graph orders and subsets,
// across word boundaries.
TEST(Permuted, KeepsEveryPairOnSparseAndDenseRows) {
  std::mt19937_64 rng(43);
  for (double density : {0.01, 0.05, 0.5, 0.95, 0.99, 1.0}) {
    for (int n : {1, 63, 64, 65, 200}) {
      const BitGraph g = test::random_graph(n, density, rng);
      std::vector<int> all(static_cast<std::size_t>(n));
      std::iota(all.begin(), all.end(), 0);
      for (int k : {n, (n + 1) / 2}) {
        std::shuffle(all.begin(), all.end(), rng);
        const std::vector<int> vertices(all.begin(), all.begin() + k);
        const BitGraph h = detail::permuted(g, vertices);
        ASSERT_EQ(h.size(), k);
        for (int i = 0; i < k; ++i) {
          for (int j = 0; j < k; ++j) {
            ASSERT_EQ(h.adjacent(i, j), g.adjacent(vertices[static_cast<std::size_t>(i)],
                                                   vertices[static_cast<std::size_t>(j)]))
                << "density " << density << " n " << n << " k " << k << " pair " << i << "," << j;
          }
        }
      }
    }
  }
}

TEST(CoreDecomposition, MatchesNaivePeeling) {
  std::mt19937_64 rng(17);
  for (int rep = 0; rep < 30; ++rep) {
    const BitGraph g = test::random_graph(40, 0.05 + 0.03 * rep, rng);
    const auto cd = core_decomposition(g);
    // Oracle: core(v) = largest k such that v survives repeatedly deleting vertices of degree < k.
    std::vector<int> core(g.size(), 0);
    for (int k = 1; k < g.size(); ++k) {
      std::vector<bool> alive(g.size(), true);
      for (bool changed = true; changed;) {
        changed = false;
        for (int u = 0; u < g.size(); ++u) {
          if (!alive[u]) continue;
          int d = 0;
          for (int w = 0; w < g.size(); ++w) d += alive[w] && g.adjacent(u, w);
          if (d < k) alive[u] = false, changed = true;
        }
      }
      for (int v = 0; v < g.size(); ++v)
        if (alive[v]) core[v] = k;
    }
    ASSERT_EQ(cd.core, core);
    ASSERT_EQ(cd.order.size(), static_cast<std::size_t>(g.size()));
  }
}

}  // namespace
}  // namespace verifybench

// bbmcx-sat (cliques/detail/sat_bb.hpp): the incremental MaxSAT bound over the colour classes.
#include <filesystem>
#include <fstream>
#include <sstream>

#include "cliques/detail/sat_bb.hpp"
#include "datasets/dimacs.hpp"

namespace verifybench {
namespace {

TEST(MaxSatBound, MatchesBruteForceOnManyRandomGraphsOfVariedDensity) {
  register_clique_algorithms();
  std::mt19937_64 rng(32002);
  for (int n : {20, 26, 30, 34}) {
    for (double density : {0.2, 0.4, 0.6, 0.75, 0.85, 0.92, 0.97}) {
      for (int rep = 0; rep < 4; ++rep) {
        const BitGraph g = test::random_graph(n, density, rng);
        const auto r = CliqueAlgorithms::get("bbmcx-sat").run(g, {});
        ASSERT_TRUE(r.optimal);
        ASSERT_TRUE(g.is_clique(r.clique));
        ASSERT_EQ(static_cast<int>(r.clique.size()), test::brute_force_clique_number(g))
            << "n=" << n << " density=" << density << " rep=" << rep;
      }
    }
  }
}

TEST(MaxSatBound, AutoOnDenseGraphsMatchesBruteForce) {
  // auto searches graphs of density >= 0.85 with the MaxSAT bound (cliques/bbmc_variants.cpp).
  register_clique_algorithms();
  std::mt19937_64 rng(32006);
  for (int n : {24, 30, 36}) {
    for (double density : {0.86, 0.9, 0.94, 0.97, 0.99}) {
      for (int rep = 0; rep < 4; ++rep) {
        const BitGraph g = test::random_graph(n, density, rng);
        const auto r = CliqueAlgorithms::get("auto").run(g, {});
        ASSERT_TRUE(r.optimal);
        ASSERT_TRUE(g.is_clique(r.clique));
        ASSERT_EQ(static_cast<int>(r.clique.size()), test::brute_force_clique_number(g))
            << "n=" << n << " density=" << density << " rep=" << rep;
      }
    }
  }
}

TEST(MaxSatBound, AutoHandsLongSparseSearchesToTheDecomposition) {
  // On sparse graphs that are no near-clique, auto's BBMCX hands the search to the decomposition
  // with the MaxSAT bound after decompose_after_words rows coloured (cliques/bbmc_variants.cpp):
  // here after 20 nodes of these 2-word graphs, so more nodes mean it did; both ways must meet
  // the brute-force clique number.
  register_clique_algorithms();
  CliqueSearchParams params;
  params.decompose_after_words = 40;
  std::mt19937_64 rng(32007);
  int handed = 0, graphs = 0;
  for (int n : {60, 80, 100}) {
    for (double density : {0.2, 0.3, 0.4, 0.48}) {
      for (int rep = 0; rep < 4; ++rep, ++graphs) {
        const BitGraph g = test::random_graph(n, density, rng);
        const auto r = CliqueAlgorithms::get("auto").run(g, params);
        ASSERT_TRUE(r.optimal);
        ASSERT_TRUE(g.is_clique(r.clique));
        ASSERT_EQ(static_cast<int>(r.clique.size()), test::brute_force_clique_number(g))
            << "n=" << n << " density=" << density << " rep=" << rep;
        handed += r.nodes > 20;
      }
    }
  }
  EXPECT_GE(handed, graphs / 4) << "the hand-off was not exercised";
}

TEST(MaxSatBound, AutoSearchesLocallyUpFrontOnSparseGraphsWithAWidePrunedGraph) {
  // A complete k-partite graph (parts of 10) among isolated vertices, with a 5-cycle inside the
  // first part: omega = k + 1 (an edge of the cycle and one vertex of each other part), and no
  // colouring has fewer than k + 2 colours (the cycle needs 3), so no colouring proves a clique.
  // The whole graph is sparse and the clique about 1/10 of the pruned graph: wider than a
  // near-clique (1/8) and within 1/12, where auto runs the local search up front on sparse graphs
  // (kWideLocalRatio); the lidar_pair FPFH 0.3 k10 dump's kind. Without the cycle omega = k and
  // the greedy colouring (one part a colour) proves the greedy clique: no local search runs.
  register_clique_algorithms();
  for (const bool cycle : {true, false}) {
    for (const int k : {6, 9, 12}) {
      const int part = 10, padding = 600;
      BitGraph g(k * part + padding);
      for (int u = 0; u < k * part; ++u)
        for (int v = u + 1; v < k * part; ++v)
          if (u / part != v / part) g.add_edge(u, v);
      if (cycle)
        for (int i = 0; i < 5; ++i) g.add_edge(i, (i + 1) % 5);
      const std::string what =
          "k=" + std::to_string(k) + (cycle ? " with" : " without") + " the cycle";
      const auto r = CliqueAlgorithms::get("auto").run(g, {});
      ASSERT_TRUE(r.optimal) << what;
      ASSERT_TRUE(g.is_clique(r.clique)) << what;
      EXPECT_EQ(static_cast<int>(r.clique.size()), cycle ? k + 1 : k) << what;
      if (cycle) {
        EXPECT_GT(r.local_search_steps, 0) << what << ": no local search up front";
      } else {
        EXPECT_EQ(r.local_search_steps, 0) << what << ": a local search the colouring spares";
      }
    }
  }
}

TEST(MaxSatBound, AutoRunsTheLocalSearchBetweenSubproblemsOnDenseGraphsThatAreNoNearClique) {
  // Density 0.5-0.75 with the clique far under an eighth of the graph: auto runs bbmcx-ls's local
  // search between the decomposition's subproblems (degrees spread as G(n, p)'s; regular graphs
  // keep BBMCX's interleave, tests/test_decomposition.cpp). Checked against the oracles.
  std::mt19937_64 rng(32008);
  int interleaved = 0;
  for (int n : {120, 150}) {
    for (double density : {0.5, 0.6, 0.7, 0.75}) {
      CliqueSearchResult r;
      test::expect_auto_matches_oracles(
          test::random_graph(n, density, rng),
          "n=" + std::to_string(n) + " density=" + std::to_string(density), &r);
      if (HasFatalFailure()) return;
      interleaved += r.local_search_steps > 0;
    }
  }
  EXPECT_GE(interleaved, 6) << "the interleaved local search was not exercised";
}

TEST(MaxSatBound, NeverPrunesBelowTheCliqueNumber) {
  // With the incumbent at omega - 1 every bound in the tree must stay >= omega on the way to a
  // maximum clique (one bound below omega would prune it); with omega, nothing is found.
  std::mt19937_64 rng(32003);
  for (int rep = 0; rep < 120; ++rep) {
    const int n = 12 + rep % 25;
    const double density = 0.3 + 0.65 * static_cast<double>(rep % 11) / 10.0;
    const BitGraph g = test::random_graph(n, density, rng);
    const int omega = test::brute_force_clique_number(g);
    // With and without Re-NUMBER, failed literals and relaxation (auto's dense paths go without
    // the first two).
    for (int bits = 0; bits < 8; ++bits) {
      const detail::SatOptions options{(bits & 1) != 0, (bits & 2) != 0, (bits & 4) != 0};
      detail::SearchBudget budget = detail::make_budget({});
      detail::SatBranchAndBound below(g, omega - 1, budget, options);
      below.run();
      ASSERT_EQ(static_cast<int>(below.best().size()), omega)
          << "rep " << rep << " options " << options.renumber << options.failed_literals
          << options.relax;
      ASSERT_TRUE(g.is_clique(below.best()));
      detail::SatBranchAndBound at(g, omega, budget, options);
      at.run();
      ASSERT_TRUE(at.best().empty()) << "rep " << rep;
      EXPECT_FALSE(budget.stopped);
    }
  }
}

TEST(MaxSatBound, AbsorbsBranchingVerticesOnDenseGraphs) {
  // The test is not idle: on a dense random graph it takes vertices out of the branching sets.
  std::mt19937_64 rng(32004);
  const BitGraph g = test::random_graph(90, 0.9, rng);
  detail::SearchBudget budget = detail::make_budget({});
  detail::SatBranchAndBound bb(g, 0, budget);
  bb.run();
  EXPECT_GT(bb.absorbed(), 0);
  EXPECT_TRUE(g.is_clique(bb.best()));
}

TEST(MaxSatBound, RelaxedSubsetsKeepTheCliqueNumberOnDenseGraphs) {
  // Relaxation (SatOptions::relax) keeps refuted classes in the later tests: on dense graphs it
  // must run (subsets relaxed) and meet the brute-force clique number, alone and with the other
  // options, from no incumbent and from omega - 1.
  std::mt19937_64 rng(32009);
  long long relaxed = 0;
  for (int rep = 0; rep < 24; ++rep) {
    const int n = 28 + rep % 9;
    const double density = 0.8 + 0.18 * static_cast<double>(rep % 6) / 5.0;
    const BitGraph g = test::random_graph(n, density, rng);
    const int omega = test::brute_force_clique_number(g);
    for (const detail::SatOptions options : {detail::SatOptions{false, false, true},
                                             detail::SatOptions{true, true, true}}) {
      for (const int incumbent : {0, omega - 1}) {
        detail::SearchBudget budget = detail::make_budget({});
        detail::SatBranchAndBound bb(g, incumbent, budget, options);
        bb.run();
        ASSERT_EQ(static_cast<int>(bb.best().size()), omega) << "rep " << rep;
        ASSERT_TRUE(g.is_clique(bb.best()));
        relaxed += bb.relaxed();
      }
    }
  }
  EXPECT_GT(relaxed, 0) << "no subset was relaxed";
}

TEST(MaxSatBound, TakesTheInterleavedLocalSearchsCliqueAsItsIncumbent) {
  // With a node limit of two the search alone ends inside its root, short of omega (brute
  // force) on every graph; the local search interleaved there (its turn comes at the first node)
  // reaches omega, and that clique is what the search reports.
  std::mt19937_64 rng(32010);
  for (int rep = 0; rep < 12; ++rep) {
    const int n = 30 + rep;
    const double density = 0.85 + 0.1 * static_cast<double>(rep % 4) / 3.0;
    const BitGraph g = test::random_graph(n, density, rng);
    const int omega = test::brute_force_clique_number(g);
    CliqueSearchParams limited;
    limited.node_limit = 2;
    detail::SearchBudget alone_budget = detail::make_budget(limited);
    detail::SatBranchAndBound alone(g, 0, alone_budget, detail::SatOptions{false, false, true});
    alone.run();
    ASSERT_LT(static_cast<int>(alone.best().size()), omega) << "rep " << rep;

    LocalSearchParams lp;
    lp.seed = 7 + static_cast<std::uint64_t>(rep);
    LocalSearch helper(g, lp);
    detail::SearchBudget budget = detail::make_budget(limited);
    detail::SatBranchAndBound bb(g, 0, budget, detail::SatOptions{false, false, true});
    bb.interleave(&helper, 1000LL * n, 0.05);
    bb.run();
    ASSERT_EQ(static_cast<int>(bb.best().size()), omega) << "rep " << rep;
    ASSERT_TRUE(g.is_clique(bb.best())) << "rep " << rep;
  }
}

TEST(MaxSatBound, MatchesKnownDimacsCliqueNumbers) {
  const std::filesystem::path dir = std::filesystem::path(VERIFYBENCH_SHARED_DATA) / "dimacs";
  if (!std::filesystem::exists(dir / "MANIFEST.tsv")) GTEST_SKIP() << "shared data absent";
  register_clique_algorithms();
  std::ifstream manifest(dir / "MANIFEST.tsv");
  std::string line;
  std::getline(manifest, line);  // header
  int solved = 0;
  while (std::getline(manifest, line)) {
    std::istringstream fields(line);
    std::string name;
    int n = 0, omega = 0;
    long long m = 0;
    if (!(fields >> name >> n >> m >> omega)) continue;
    if (n > 300 || !std::filesystem::exists(dir / (name + ".clq"))) continue;  // the small ones
    const BitGraph g = read_dimacs((dir / (name + ".clq")).string());
    CliqueSearchParams p;
    p.node_limit = 300'000;  // deterministic budget; the small ones finish well within it
    for (const char* algorithm : {"bbmcx-sat", "auto"}) {
      const auto r = CliqueAlgorithms::get(algorithm).run(g, p);
      ASSERT_TRUE(g.is_clique(r.clique)) << algorithm << " " << name;
      EXPECT_LE(static_cast<int>(r.clique.size()), omega) << algorithm << " " << name;
      EXPECT_GE(r.upper_bound, omega) << algorithm << " " << name;
      if (r.optimal) {
        EXPECT_EQ(static_cast<int>(r.clique.size()), omega) << algorithm << " " << name;
        solved += algorithm == std::string("bbmcx-sat");
      }
    }
  }
  EXPECT_GE(solved, 5);
}

TEST(MaxSatBound, SameCliqueForAnyThreadCountAndLimitsStopIt) {
  register_clique_algorithms();
  std::mt19937_64 rng(32005);
  const BitGraph g = test::random_graph(150, 0.8, rng);
  for (const char* algorithm : {"bbmcx-sat", "auto"}) {
    CliqueSearchParams one, four;
    four.threads = 4;
    const auto a = CliqueAlgorithms::get(algorithm).run(g, one);
    const auto b = CliqueAlgorithms::get(algorithm).run(g, four);
    EXPECT_TRUE(a.optimal && b.optimal) << algorithm;
    EXPECT_EQ(a.clique, b.clique) << algorithm;
  }
  CliqueSearchParams limited;
  limited.node_limit = 50;
  const auto r = CliqueAlgorithms::get("bbmcx-sat").run(g, limited);
  EXPECT_TRUE(r.stopped);
  EXPECT_FALSE(r.optimal);
  EXPECT_TRUE(g.is_clique(r.clique));
  CliqueSearchParams timed;
  timed.time_limit_s = 1e-9;
  const auto t = CliqueAlgorithms::get("bbmcx-sat").run(g, timed);
  EXPECT_TRUE(t.stopped);
  EXPECT_TRUE(g.is_clique(t.clique));
}

}  // namespace
}  // namespace verifybench
