#pragma once
// Helpers shared by the tests: seeded random graphs and transforms, a brute-force clique oracle,
// planar poses, and a runner for the CLI.
#include <sys/wait.h>

#include <algorithm>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "core/correspondences.hpp"
#include "graph/bitgraph.hpp"

namespace verifybench::test {

inline BitGraph random_graph(int n, double density, std::mt19937_64& rng) {
  BitGraph g(n);
  std::bernoulli_distribution edge(density);
  for (int u = 0; u < n; ++u) {
    for (int v = u + 1; v < n; ++v) {
      if (edge(rng)) g.add_edge(u, v);
    }
  }
  return g;
}

/// Joins k random vertices of g into a clique; returns them in ascending order.
inline std::vector<int> plant_clique(BitGraph& g, int k, std::mt19937_64& rng) {
  std::vector<int> planted(static_cast<std::size_t>(g.size()));
  for (int v = 0; v < g.size(); ++v) planted[static_cast<std::size_t>(v)] = v;
  std::shuffle(planted.begin(), planted.end(), rng);
  planted.resize(static_cast<std::size_t>(k));
  for (std::size_t a = 0; a < planted.size(); ++a)
    for (std::size_t b = a + 1; b < planted.size(); ++b) g.add_edge(planted[a], planted[b]);
  std::sort(planted.begin(), planted.end());
  return planted;
}

/// A maximum clique by exhaustive include/exclude recursion (n <= ~30): obviously correct, slow.
inline std::vector<int> brute_force_clique(const BitGraph& g) {
  std::vector<int> best, chosen;
  auto rec = [&](auto&& self, int v) -> void {
    if (chosen.size() + static_cast<std::size_t>(g.size() - v) <= best.size()) return;
    if (v == g.size()) {
      best = chosen;  // larger than best, or the line above had returned
      return;
    }
    bool fits = true;
    for (int u : chosen) fits = fits && g.adjacent(u, v);
    if (fits) {
      chosen.push_back(v);
      self(self, v + 1);
      chosen.pop_back();
    }
    self(self, v + 1);
  };
  rec(rec, 0);
  return best;
}

/// Clique number by the same recursion.
inline int brute_force_clique_number(const BitGraph& g) {
  return static_cast<int>(brute_force_clique(g).size());
}

template <int Dim>
Rigid<Dim> random_rigid(std::mt19937_64& rng, double max_translation = 5.0) {
  std::normal_distribution<double> g(0.0, 1.0);
  std::uniform_real_distribution<double> t(-max_translation, max_translation);
  Rigid<Dim> T = Rigid<Dim>::Identity();
  if constexpr (Dim == 2) {
    T.linear() = Eigen::Rotation2Dd(std::uniform_real_distribution<double>(-M_PI, M_PI)(rng))
                     .toRotationMatrix();
  } else {
    T.linear() = Eigen::Quaterniond(g(rng), g(rng), g(rng), g(rng)).normalized().toRotationMatrix();
  }
  for (int d = 0; d < Dim; ++d) T.translation()(d) = t(rng);
  return T;
}

/// A pose in the plane: yaw about z, position (x, y, 0).
inline Rigid<3> planar_pose(double x, double y, double yaw) {
  Rigid<3> T = Rigid<3>::Identity();
  T.linear() = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  T.translation() << x, y, 0.0;
  return T;
}

struct CliRun {
  int code;
  std::string output;  ///< stdout and stderr together
};

/// Runs the verifybench CLI of this build with `args` (a shell line).
inline CliRun run_cli(const std::string& args) {
  const std::string cmd = std::string(VERIFYBENCH_CLI) + " " + args + " 2>&1";
  FILE* pipe = popen(cmd.c_str(), "r");
  std::string out;
  char buf[4096];
  while (pipe && fgets(buf, sizeof buf, pipe)) out += buf;
  const int status = pipe ? pclose(pipe) : -1;
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, out};
}

}  // namespace verifybench::test
