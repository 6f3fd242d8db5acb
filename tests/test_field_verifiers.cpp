// The field's verifiers (gnc-tls, teaser, sc2-pcr; robin-gnc, quatro, turboreg, clipper and
// fastmac have their own oracle files and join the suites here) against oracles: GNC-TLS against exhaustive
// truncated least squares on tiny sets, TEASER's adaptive voting against a brute-force scalar TLS,
// its k-core mode against a reference peeling, the SC2 matrix against its definition by triple
// loops; and each recovers motions this test draws in its paper's outlier regime.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iostream>
#include <limits>
#include <random>
#include <tuple>

#include "core/metrics.hpp"
#include "core/rigid_fit.hpp"
#include "generators/synthetic.hpp"
#include "graph/compatibility_graph.hpp"
#include "registered_solvers.hpp"
#include "solvers/detail/sc2.hpp"
#include "solvers/detail/teaser.hpp"
#include "solvers/registry.hpp"
#include "test_util.hpp"

namespace verifybench {
namespace {

/// sum_i min(r_i^2, c^2) of a motion: the TLS cost.
template <int Dim>
double tls_cost(const Correspondences<Dim>& corr, const Rigid<Dim>& T, double c) {
  double cost = 0.0;
  for (Eigen::Index i = 0; i < corr.size(); ++i) {
    cost += std::min((T * corr.source.col(i) - corr.target.col(i)).squaredNorm(), c * c);
  }
  return cost;
}

/// The TLS optimum by trying every subset as the inlier set: the least-squares fit of the
/// optimum's own inlier set costs no more than the optimum, so the best subset fit is optimal.
template <int Dim>
double exhaustive_tls(const Correspondences<Dim>& corr, double c) {
  const int n = static_cast<int>(corr.size());
  double best = n * c * c;  // everything an outlier
  for (std::uint32_t mask = 1; mask < (1u << n); ++mask) {
    std::vector<int> subset;
    for (int i = 0; i < n; ++i) {
      if ((mask >> i) & 1) subset.push_back(i);
    }
    if (const auto T = fit_rigid(corr, subset)) best = std::min(best, tls_cost(corr, *T, c));
  }
  return best;
}

/// n points in a 2 m cube, `outliers` of them with random targets, inliers moved by a drawn motion
/// with 0.01 m noise.
template <int Dim>
LabeledSet<Dim> tiny_set(int n, int outliers, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::normal_distribution<double> noise(0.0, 0.01);
  LabeledSet<Dim> set;
  set.truth.T_target_source = test::random_rigid<Dim>(rng, 1.0);
  set.corr.source.resize(Dim, n);
  set.corr.target.resize(Dim, n);
  for (int i = 0; i < n; ++i) {
    for (int d = 0; d < Dim; ++d) set.corr.source(d, i) = u(rng);
    if (i < outliers) {
      for (int d = 0; d < Dim; ++d) set.corr.target(d, i) = 2.0 * u(rng);
    } else {
      set.corr.target.col(i) = *set.truth.T_target_source * set.corr.source.col(i);
      for (int d = 0; d < Dim; ++d) set.corr.target(d, i) += noise(rng);
    }
  }
  return set;
}

/// 50 sets of 8-10 correspondences, 2-3 of them outliers: GNC is a heuristic, so most, not all,
/// reach the optimum (about 96% in 3D and 98% in 2D over 200 sets); at least 45 of 50 must.
template <int Dim>
void expect_gnc_matches_exhaustive_tls() {
  const auto gnc = SolverRegistry::create("gnc-tls");
  SolverParams params;
  std::mt19937_64 rng(7 + Dim);
  int optimal = 0;
  for (int trial = 0; trial < 50; ++trial) {
    const auto set = tiny_set<Dim>(8 + trial % 3, 2 + trial % 2, rng);
    const Result<Dim> r = gnc->solve(set.corr, params);
    ASSERT_NE(r.status, Status::error) << r.message;
    const double found = tls_cost(set.corr, r.T_target_source, params.inlier_threshold);
    const double best = exhaustive_tls(set.corr, params.inlier_threshold);
    EXPECT_GE(found, best - 1e-9) << "trial " << trial;  // the oracle is the optimum
    optimal += found <= best + 1e-6;
  }
  std::cout << "[ oracle   ] " << Dim << "D: " << optimal << " of 50 at the TLS optimum\n";
  EXPECT_GE(optimal, 45);
}

TEST(GncTls, ReachesTheExhaustiveTlsOptimumOnTinySets2D) { expect_gnc_matches_exhaustive_tls<2>(); }
TEST(GncTls, ReachesTheExhaustiveTlsOptimumOnTinySets3D) { expect_gnc_matches_exhaustive_tls<3>(); }

/// TLS cost of a scalar estimate: sum_i min((x - x_i)^2 / c^2, 1).
double scalar_tls(const std::vector<double>& x, double c, double at) {
  double cost = 0.0;
  for (double v : x) cost += std::min((at - v) * (at - v) / (c * c), 1.0);
  return cost;
}

TEST(Teaser, AdaptiveVotingMatchesBruteForce) {
  // Brute force: the optimum's inlier set is a run of the sorted values, and its mean costs no
  // more; so the best mean over all runs is the optimum. A fine grid bounds it from above too.
  std::mt19937_64 rng(3);
  for (int trial = 0; trial < 200; ++trial) {
    const int n = 1 + trial % 30;
    const double c = 0.05 + 0.1 * (trial % 4);
    std::uniform_real_distribution<double> spread(-2.0, 2.0);
    std::normal_distribution<double> cluster(0.7, 0.04);
    std::vector<double> x;
    for (int i = 0; i < n; ++i) x.push_back(i % 3 == 0 ? spread(rng) : cluster(rng));
    if (trial % 10 == 0) x.push_back(x.front());  // repeated values
    std::vector<double> sorted(x);
    std::sort(sorted.begin(), sorted.end());
    double best = std::numeric_limits<double>::infinity();
    for (std::size_t a = 0; a < sorted.size(); ++a) {
      double sum = 0.0;
      for (std::size_t b = a; b < sorted.size(); ++b) {
        sum += sorted[b];
        best = std::min(best, scalar_tls(x, c, sum / static_cast<double>(b - a + 1)));
      }
    }
    double grid = std::numeric_limits<double>::infinity();
    for (double at = -2.5; at <= 2.5; at += 1e-4) grid = std::min(grid, scalar_tls(x, c, at));
    const VoteResult vote = adaptive_vote(x, c);
    const double cost = scalar_tls(x, c, vote.estimate);
    EXPECT_NEAR(cost, best, 1e-9) << "trial " << trial;
    EXPECT_LE(cost, grid + 1e-12) << "trial " << trial;
    EXPECT_NEAR(vote.cost, cost, 1e-9) << "trial " << trial;
    int consensus = 0;
    for (double v : x) consensus += std::abs(v - vote.estimate) <= c;
    EXPECT_EQ(vote.consensus, consensus);
  }
}

TEST(Teaser, KcoreModeSelectsTheReferencePeelingsMaxCore) {
  std::mt19937_64 rng(11);
  for (int trial = 0; trial < 60; ++trial) {
    const int n = 5 + trial;
    BitGraph g = test::random_graph(n, 0.05 + 0.3 * (trial % 4) / 3.0, rng);
    if (trial % 2 == 0) test::plant_clique(g, std::min(n, 4 + trial / 4), rng);
    // Reference: the k-core is what is left after removing vertices of degree < k until none is;
    // the max core is the last non-empty one.
    std::vector<int> max_core;
    for (int k = 1;; ++k) {
      std::vector<char> alive(static_cast<std::size_t>(n), 1);
      for (bool removed = true; removed;) {
        removed = false;
        for (int v = 0; v < n; ++v) {
          if (!alive[static_cast<std::size_t>(v)]) continue;
          int degree = 0;
          for (int u = 0; u < n; ++u)
            degree += alive[static_cast<std::size_t>(u)] && g.adjacent(u, v);
          if (degree < k) alive[static_cast<std::size_t>(v)] = 0, removed = true;
        }
      }
      std::vector<int> core;
      for (int v = 0; v < n; ++v) {
        if (alive[static_cast<std::size_t>(v)]) core.push_back(v);
      }
      if (core.empty()) break;
      max_core = core;
    }
    const auto selected = max_kcore_selection(g, 0.0);
    if (max_core.empty()) {  // no edge: TEASER++ falls back to its heuristic clique
      EXPECT_FALSE(selected.has_value());
      continue;
    }
    ASSERT_TRUE(selected.has_value()) << "trial " << trial;
    EXPECT_EQ(*selected, max_core) << "trial " << trial;
    EXPECT_FALSE(max_kcore_selection(g, 1.0).has_value());  // a core number is < n
  }
}

TEST(Sc2Pcr, Sc2MatrixMatchesItsDefinition) {
  for (int dim : {2, 3}) {
    SyntheticParams p;
    p.n = 30;
    p.outlier_ratio = 0.5;
    p.extent = 2.0;
    p.seed = 5 + static_cast<std::uint64_t>(dim);
    const double d_thr = 0.1;
    const auto check = [&](const auto& corr) {
      const int n = static_cast<int>(corr.size());
      const BitGraph g = build_compatibility_graph(corr, GraphParams{d_thr});
      // C_ij = [ | ||m_i - m_j|| - ||q_i - q_j|| | < d_thr ], diagonal included (d_ii = 0).
      std::vector<std::vector<int>> C(30, std::vector<int>(30));
      for (int i = 0; i < n; ++i) {
        for (int j = 0; j < n; ++j) {
          C[i][j] = std::abs((corr.source.col(i) - corr.source.col(j)).norm() -
                             (corr.target.col(i) - corr.target.col(j)).norm()) < d_thr;
        }
      }
      std::vector<int> row;
      long long nonzero = 0;
      for (int i = 0; i < n; ++i) {
        sc2_row(g, i, row);
        for (int j = 0; j < n; ++j) {
          int cc = 0;  // (C x C)_ij
          for (int k = 0; k < n; ++k) cc += C[i][k] * C[k][j];
          EXPECT_EQ(row[static_cast<std::size_t>(j)], C[i][j] * cc) << i << "," << j;
          nonzero += i != j && row[static_cast<std::size_t>(j)] > 0;
        }
      }
      EXPECT_GT(nonzero, 100);  // the inliers' block at least
    };
    if (dim == 2) {
      check(make_synthetic<2>(p).corr);
    } else {
      check(make_synthetic<3>(p).corr);
    }
  }
}

// Recovery of drawn motions in each paper's regime: solver, dim, n, outlier ratio, and for
// teaser the inlier selection mode (and the complete TIM graph).
struct Regime {
  std::string solver;
  int dim;
  int n;
  double outliers;
  int teaser_mode = TeaserParams::kExact;
  bool complete_tims = false;
  double kcore_threshold = 0.5;
  double max_translation_error = 0.1;  ///< [m]; 1 deg of rotation error in every regime
  std::string name;
};

class Recovers : public ::testing::TestWithParam<Regime> {};

template <int Dim>
void expect_recovery(const Regime& regime) {
  const auto solver = SolverRegistry::create(regime.solver);
  SolverParams params;
  params.teaser.inlier_selection = regime.teaser_mode;
  params.teaser.complete_tim_graph = regime.complete_tims;
  params.teaser.kcore_threshold = regime.kcore_threshold;
  double total_ms = 0.0;
  const int trials = 3;
  for (std::uint64_t seed = 1; seed <= trials; ++seed) {
    SyntheticParams p;
    p.n = regime.n;
    p.outlier_ratio = regime.outliers;
    p.seed = seed;
    const auto set = make_synthetic<Dim>(p);
    const auto start = std::chrono::steady_clock::now();
    const Result<Dim> r = solver->solve(set.corr, params);
    total_ms +=
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    ASSERT_EQ(r.status, Status::ok) << regime.name << " seed " << seed << ": " << r.message;
    EXPECT_LT(rotation_error_deg(r.T_target_source, *set.truth.T_target_source), 1.0) << seed;
    EXPECT_LT(translation_error(r.T_target_source, *set.truth.T_target_source),
              regime.max_translation_error)
        << seed;
    const auto s = inlier_scores(r.inliers, set.truth.labels);
    EXPECT_GT(s.precision, 0.9) << seed;
    EXPECT_GT(s.recall, 0.8) << seed;
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

Regime regime(std::string solver, int dim, int n, double outliers) {
  Regime r;
  r.solver = std::move(solver);
  r.dim = dim;
  r.n = n;
  r.outliers = outliers;
  if (r.solver == "gnc-tls") r.max_translation_error = 0.05;
  r.name = r.solver + "_" + std::to_string(dim) + "D_n" + std::to_string(n) + "_" +
           std::to_string(static_cast<int>(std::lround(outliers * 100))) + "pct";
  for (char& ch : r.name) ch = ch == '-' ? '_' : ch;
  return r;
}

Regime teaser_mode(Regime r, int mode, const std::string& tag) {
  r.teaser_mode = mode;
  r.name += "_" + tag;
  return r;
}

// GNC-TLS: the paper's registration experiments hold to 70-80% outliers; TEASER: 95% and 99%
// (its extreme-outlier experiments: 1000 correspondences, 99% outliers); SC2-PCR: 95%.
INSTANTIATE_TEST_SUITE_P(
    Regimes, Recovers,
    ::testing::Values(
        regime("gnc-tls", 2, 100, 0.7), regime("gnc-tls", 3, 100, 0.7),
        regime("teaser", 2, 1000, 0.95), regime("teaser", 3, 1000, 0.95),
        regime("teaser", 3, 1000, 0.99),
        teaser_mode(regime("teaser", 3, 1000, 0.9), TeaserParams::kHeuristic, "heuristic"),
        [] {
          Regime r = teaser_mode(regime("teaser", 3, 500, 0.8), TeaserParams::kKcore, "kcore");
          r.kcore_threshold = 0.0;  // always the max k-core, never the fallback
          return r;
        }(),
        [] {
          Regime r = regime("teaser", 3, 1000, 0.95);
          r.complete_tims = true;
          r.name += "_complete_tims";
          return r;
        }(),
        regime("sc2-pcr", 2, 1000, 0.95), regime("sc2-pcr", 3, 1000, 0.95),
        // KISS-Matcher's pruning holds to 95% here (at 99% the outliers' cores outgrow the
        // inliers': test_robin_quatro); Quatro on full SO(3) motions is out of its definition, so
        // 2D here and yaw-only 3D in test_robin_quatro; TurboReg 95-99%; CLIPPER+ 95-99%;
        // FastMAC 90-95% (its paper's KITTI / 3DMatch regime).
        regime("robin-gnc", 2, 1000, 0.95), regime("robin-gnc", 3, 1000, 0.95),
        regime("quatro", 2, 1000, 0.95), regime("turboreg", 2, 1000, 0.95),
        regime("turboreg", 3, 1000, 0.99), regime("clipper", 2, 1000, 0.95),
        regime("clipper", 3, 1000, 0.99), regime("fastmac", 2, 1000, 0.9),
        regime("fastmac", 3, 1000, 0.95)),
    [](const auto& info) { return info.param.name; });

class EachSolver : public ::testing::TestWithParam<std::string> {};

TEST_P(EachSolver, BadInputIsAnErrorAndAnEmptySetIsRejected) {
  const auto solver = SolverRegistry::create(GetParam());
  Correspondences<3> c;
  c.source = Eigen::Matrix3Xd::Random(3, 10);
  c.target = c.source;
  c.target(1, 4) = std::numeric_limits<double>::quiet_NaN();
  auto r = solver->solve(c, SolverParams{});
  EXPECT_EQ(r.status, Status::error);
  EXPECT_NE(r.message.find("correspondence 4"), std::string::npos) << r.message;
  Correspondences<2> mismatched{Eigen::Matrix2Xd::Zero(2, 4), Eigen::Matrix2Xd::Zero(2, 5), {}, {}};
  EXPECT_EQ(solver->solve(mismatched, SolverParams{}).status, Status::error);
  SolverParams bad;
  bad.inlier_threshold = -1;
  EXPECT_EQ(solver->solve(Correspondences<3>{c.source, c.source, {}, {}}, bad).status,
            Status::error);
  // An empty set is nothing to verify, as for every solver of the registry (test_solvers).
  for (const auto& empty : {solver->solve(Correspondences<2>{}, SolverParams{}).status,
                            solver->solve(Correspondences<3>{}, SolverParams{}).status}) {
    EXPECT_EQ(empty, Status::rejected);
  }
  // One correspondence, or a few coincident ones, pin no motion: rejected, not a crash.
  Correspondences<3> one{Eigen::Matrix3Xd::Zero(3, 1), Eigen::Matrix3Xd::Zero(3, 1), {}, {}};
  EXPECT_EQ(solver->solve(one, SolverParams{}).status, Status::rejected);
  Correspondences<2> same{Eigen::Matrix2Xd::Ones(2, 6), Eigen::Matrix2Xd::Ones(2, 6), {}, {}};
  EXPECT_EQ(solver->solve(same, SolverParams{}).status, Status::rejected);
}

TEST_P(EachSolver, AMicrosecondLimitReturnsPromptly) {
  const auto solver = SolverRegistry::create(GetParam());
  SyntheticParams p;
  p.n = 1000;
  p.outlier_ratio = 0.95;
  SolverParams params;
  params.time_limit_s = 1e-6;
  for (int dim : {2, 3}) {
    const auto start = std::chrono::steady_clock::now();
    const Status status = dim == 2 ? solver->solve(make_synthetic<2>(p).corr, params).status
                                   : solver->solve(make_synthetic<3>(p).corr, params).status;
    EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 1.0);
    EXPECT_NE(status, Status::error) << dim;  // time_limit, or a finished result
  }
}

TEST_P(EachSolver, ScoresNeverExceedTheirBound) {
  // The calibrated rule screens null sets with score_bound: it must hold for every solve, and be
  // exact (n) on a set of inliers only (one clique of every graph it bounds by).
  const auto solver = SolverRegistry::create(GetParam());
  SolverParams params;
  params.eps = 0.4;
  params.inlier_threshold = 0.2;
  for (int mode : {TeaserParams::kExact, TeaserParams::kKcore}) {
    params.teaser.inlier_selection = mode;
    params.teaser.kcore_threshold = 0.0;
    for (std::uint64_t seed = 1; seed <= 20; ++seed) {
      SyntheticParams p;
      p.n = 16;
      p.outlier_ratio = seed % 3 == 0 ? 0.0 : 0.5;
      p.extent = 2.0;
      p.seed = seed;
      const auto set = make_synthetic<3>(p);
      const auto score = static_cast<int>(solver->solve(set.corr, params).inliers.size());
      for (int part_size : {2048, 64, 8, 5}) {
        const auto bound = solver->score_bound(set.corr, params, part_size);
        ASSERT_TRUE(bound.has_value());
        EXPECT_LE(score, *bound) << "seed " << seed << " part size " << part_size;
      }
    }
    SyntheticParams clean;
    clean.n = 200;
    clean.outlier_ratio = 0.0;
    EXPECT_EQ(solver->score_bound(make_synthetic<3>(clean).corr, params, 2048), 200);
  }
}

INSTANTIATE_TEST_SUITE_P(FieldVerifiers, EachSolver,
                         ::testing::Values("gnc-tls", "teaser", "sc2-pcr", "robin-gnc", "quatro",
                                           "turboreg", "clipper", "fastmac"),
                         [](const auto& info) {
                           std::string name = info.param;
                           std::replace(name.begin(), name.end(), '-', '_');
                           return name;
                         });

TEST(GraphVerifiers, RefuseAGraphOverTheMemoryCap) {  // SC2 is n x n: never built past the cap
  for (const char* name : {"sc2-pcr", "teaser", "robin-gnc", "quatro", "turboreg", "clipper",
                           "fastmac"}) {
    Correspondences<3> c{
        Eigen::Matrix3Xd::Random(3, 3000), Eigen::Matrix3Xd::Random(3, 3000), {}, {}};
    SolverParams params;
    params.max_graph_bytes = 1000;
    const auto r = SolverRegistry::create(name)->solve(c, params);
    EXPECT_EQ(r.status, Status::error) << name;
    EXPECT_NE(r.message.find("3000 vertices"), std::string::npos) << r.message;
  }
}

}  // namespace
}  // namespace verifybench
