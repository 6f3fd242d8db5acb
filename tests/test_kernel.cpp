// The complement's vertex-cover reductions as a clique kernel (cliques/kernel.cpp), against the
// brute force and against graphs whose clique numbers are known.
#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "cliques/detail/kernel.hpp"
#include "test_util.hpp"

namespace verifybench {
namespace {

// The complement of a graph given by its (sparse) edge list.
BitGraph complement_of(int n, const std::vector<std::pair<int, int>>& h_edges) {
  BitGraph h(n), g(n);
  for (auto [u, v] : h_edges) h.add_edge(u, v);
  for (int u = 0; u < n; ++u) {
    for (int v = u + 1; v < n; ++v) {
      if (!h.adjacent(u, v)) g.add_edge(u, v);
    }
  }
  return g;
}

TEST(CliqueKernel, KeepsTheCliqueNumberAndLiftsToACliqueOfG) {
  std::mt19937_64 rng(67001);
  int reduced = 0;
  for (int rep = 0; rep < 120; ++rep) {
    const int n = 12 + rep % 29;
    const double density = 0.70 + 0.0025 * rep;  // 0.70 .. 0.998: the complement's degree 0 .. 12
    const BitGraph g = test::random_graph(n, density, rng);
    const detail::CliqueKernel kernel(g);
    const int omega = test::brute_force_clique_number(g);
    const std::vector<int> inner = test::brute_force_clique(kernel.graph());
    ASSERT_EQ(static_cast<int>(inner.size()) + kernel.credit(), omega) << "rep " << rep;
    const std::vector<int> lifted = kernel.lift(inner);
    ASSERT_EQ(static_cast<int>(lifted.size()), omega) << "rep " << rep;
    ASSERT_TRUE(g.is_clique(lifted)) << "rep " << rep;
    // Any clique of the kernel, not only a maximum one, lifts to a clique credit() larger.
    if (!inner.empty()) {
      const std::vector<int> smaller(inner.begin() + 1, inner.end());
      const std::vector<int> lifted_smaller = kernel.lift(smaller);
      ASSERT_EQ(lifted_smaller.size(), smaller.size() + static_cast<std::size_t>(kernel.credit()));
      ASSERT_TRUE(g.is_clique(lifted_smaller)) << "rep " << rep;
    }
    if (kernel.graph().size() < n) ++reduced;
  }
  EXPECT_GE(reduced, 60);  // the rules fire on most of these dense graphs
}

TEST(CliqueKernel, FoldsTheComplementOfAPathAndOfACycleAway) {
  // H a path of n vertices: alpha = ceil(n / 2); a cycle: floor(n / 2). Folding and the
  // simplicial rule leave nothing of the path and at most a triangle's complement of the cycle.
  for (int n = 3; n <= 40; ++n) {
    std::vector<std::pair<int, int>> path, cycle;
    for (int v = 0; v + 1 < n; ++v) path.push_back({v, v + 1});
    cycle = path;
    cycle.push_back({n - 1, 0});
    const BitGraph gp = complement_of(n, path), gc = complement_of(n, cycle);
    const detail::CliqueKernel kp(gp), kc(gc);
    EXPECT_EQ(kp.graph().size(), 0) << n;
    EXPECT_EQ(kp.credit(), (n + 1) / 2) << n;
    const std::vector<int> cp = kp.lift({});
    EXPECT_EQ(static_cast<int>(cp.size()), (n + 1) / 2) << n;
    EXPECT_TRUE(gp.is_clique(cp)) << n;
    const std::vector<int> inner = test::brute_force_clique(kc.graph());
    EXPECT_EQ(static_cast<int>(inner.size()) + kc.credit(), n / 2) << n;
    EXPECT_TRUE(gc.is_clique(kc.lift(inner))) << n;
    EXPECT_LE(kc.graph().size(), 3) << n;
  }
}

TEST(CliqueKernel, DropsDominatedVerticesAndLeavesARegularComplementAlone) {
  // u and v non-adjacent, N(u) inside N(v): u goes. Here u = 0 sees {2, 3}, v = 1 sees {2, 3, 4}.
  BitGraph g(6);
  for (auto [a, b] : std::vector<std::pair<int, int>>{
           {0, 2}, {0, 3}, {1, 2}, {1, 3}, {1, 4}, {2, 3}, {4, 5}, {3, 5}}) {
    g.add_edge(a, b);
  }
  const detail::CliqueKernel k(g);
  const std::vector<int> inner = test::brute_force_clique(k.graph());
  EXPECT_EQ(static_cast<int>(inner.size()) + k.credit(), test::brute_force_clique_number(g));
  for (int v : k.kept()) EXPECT_NE(v, 0);
  // The complement of a 3-regular graph with no triangle and no two vertices sharing their
  // neighbours (the Petersen graph): no rule applies, the kernel is the graph.
  std::vector<std::pair<int, int>> petersen;
  for (int i = 0; i < 5; ++i) {
    petersen.push_back({i, (i + 1) % 5});
    petersen.push_back({i, i + 5});
    petersen.push_back({5 + i, 5 + (i + 2) % 5});
  }
  const detail::CliqueKernel kp(complement_of(10, petersen));
  EXPECT_EQ(kp.graph().size(), 10);
  EXPECT_EQ(kp.credit(), 0);
}

}  // namespace
}  // namespace verifybench
