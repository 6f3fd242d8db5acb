// `robin-gnc` (KISS-Matcher's verifier) and `quatro` against oracles: ROBIN's max k-core against a
// reference peeling written here, Quatro's closed-form yaw against a brute-force scan of its cost
// and its GNC-TLS yaw against a brute-force scan of the truncated least-squares cost; each
// recovers motions drawn here in its paper's regime, quatro's rotation stays about z under roll,
// and both give the same answer for any thread count (the registry's contract -- bad input,
// empty sets, a microsecond limit, bounds -- runs in test_field_verifiers' EachSolver).
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iostream>
#include <limits>
#include <random>

#include "core/metrics.hpp"
#include "core/rigid_fit.hpp"
#include "generators/synthetic.hpp"
#include "registered_solvers.hpp"
#include "solvers/detail/quatro.hpp"
#include "solvers/registry.hpp"
#include "test_util.hpp"

namespace verifybench {
namespace {

// ---------------------------------------------------------------------------------------------
// ROBIN's max k-core.

/// Reference: the k-core is what is left after deleting vertices of degree < k until none is;
/// the max core is the last non-empty one (k >= 1).
std::vector<int> reference_max_core(const BitGraph& g) {
  const int n = g.size();
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
    if (core.empty()) return max_core;
    max_core = core;
  }
}

TEST(Robin, MaxCoreModeSelectsTheReferencePeelingsMaxCore) {
  std::mt19937_64 rng(17);
  int nonempty = 0;
  for (int trial = 0; trial < 80; ++trial) {
    const int n = 4 + trial;
    BitGraph g = test::random_graph(n, 0.02 + 0.3 * (trial % 5) / 4.0, rng);
    if (trial % 2 == 0) test::plant_clique(g, std::min(n, 3 + trial / 5), rng);
    const std::vector<int> expected = reference_max_core(g);
    const RobinSelection got = robin_select(g, /*max_clique=*/false, 10.0, 1, 1);
    EXPECT_EQ(got.vertices, expected) << "trial " << trial;  // empty with no edge
    EXPECT_FALSE(got.stopped);
    nonempty += !expected.empty();
  }
  EXPECT_GT(nonempty, 70);
}

TEST(Robin, MaxCliqueModeSelectsAMaximumClique) {
  std::mt19937_64 rng(19);
  for (int trial = 0; trial < 30; ++trial) {
    BitGraph g = test::random_graph(12 + trial % 10, 0.3 + 0.02 * (trial % 10), rng);
    const RobinSelection got = robin_select(g, /*max_clique=*/true, 10.0, 1, 1);
    EXPECT_EQ(static_cast<int>(got.vertices.size()), test::brute_force_clique_number(g));
    for (std::size_t a = 0; a < got.vertices.size(); ++a)
      for (std::size_t b = a + 1; b < got.vertices.size(); ++b)
        EXPECT_TRUE(g.adjacent(got.vertices[a], got.vertices[b]));
  }
}

// ---------------------------------------------------------------------------------------------
// Quatro's yaw.

/// A few planar TIMs: `outliers` of them random, the rest a_i rotated by `yaw` plus noise.
void tiny_tims(int n, int outliers, double yaw, std::mt19937_64& rng, Eigen::Matrix2Xd& a,
               Eigen::Matrix2Xd& b) {
  std::uniform_real_distribution<double> u(-1.5, 1.5);
  std::normal_distribution<double> noise(0.0, 0.02);
  const Eigen::Matrix2d R = Eigen::Rotation2Dd(yaw).toRotationMatrix();
  a.resize(2, n);
  b.resize(2, n);
  for (int i = 0; i < n; ++i) {
    a.col(i) << u(rng), u(rng);
    if (i < outliers) {
      b.col(i) << u(rng), u(rng);
    } else {
      b.col(i) = R * a.col(i) + Eigen::Vector2d(noise(rng), noise(rng));
    }
  }
}

/// sum_i f(||b_i - R(theta) a_i||^2) on a grid of `steps` yaws over [-pi, pi): the argmin and min.
template <class F>
std::pair<double, double> scan_yaw(const Eigen::Matrix2Xd& a, const Eigen::Matrix2Xd& b, F&& f,
                                   int steps) {
  double best = std::numeric_limits<double>::infinity(), at = 0.0;
  for (int s = 0; s < steps; ++s) {
    const double theta = -M_PI + 2.0 * M_PI * s / steps;
    const double c = std::cos(theta), sn = std::sin(theta);
    double cost = 0.0;
    for (Eigen::Index i = 0; i < a.cols(); ++i) {
      const double rx = b(0, i) - (c * a(0, i) - sn * a(1, i));
      const double ry = b(1, i) - (sn * a(0, i) + c * a(1, i));
      cost += f(static_cast<int>(i), rx * rx + ry * ry);
    }
    if (cost < best) best = cost, at = theta;
  }
  return {at, best};
}

double angle_gap(double x, double y) { return std::abs(std::remainder(x - y, 2.0 * M_PI)); }

TEST(Quatro, ClosedFormYawIsTheArgminOfTheWeightedCost) {
  std::mt19937_64 rng(23);
  std::uniform_real_distribution<double> weight(0.0, 1.0), yaw(-M_PI, M_PI);
  const int steps = 200000;  // grid step 3.1e-5 rad
  for (int trial = 0; trial < 40; ++trial) {
    Eigen::Matrix2Xd a, b;
    tiny_tims(3 + trial % 6, trial % 3, yaw(rng), rng, a, b);
    std::vector<double> w(static_cast<std::size_t>(a.cols()));
    for (double& x : w) x = trial % 4 == 0 ? 1.0 : weight(rng);
    const auto closed = weighted_yaw(a, b, w);
    ASSERT_TRUE(closed.has_value());
    const auto weighted = [&](int i, double r2) { return w[static_cast<std::size_t>(i)] * r2; };
    const auto [grid_at, grid_min] = scan_yaw(a, b, weighted, steps);
    double closed_cost = 0.0;
    const Eigen::Matrix2d R = Eigen::Rotation2Dd(*closed).toRotationMatrix();
    for (Eigen::Index i = 0; i < a.cols(); ++i)
      closed_cost += w[static_cast<std::size_t>(i)] * (b.col(i) - R * a.col(i)).squaredNorm();
    EXPECT_LE(closed_cost, grid_min + 1e-12) << "trial " << trial;  // no grid point does better
    EXPECT_LT(angle_gap(*closed, grid_at), 1e-3) << "trial " << trial;
  }
  // No weight on a non-zero TIM: undetermined.
  Eigen::Matrix2Xd a = Eigen::Matrix2Xd::Random(2, 4), b = Eigen::Matrix2Xd::Random(2, 4);
  EXPECT_FALSE(weighted_yaw(a, b, std::vector<double>(4, 0.0)).has_value());
}

TEST(Quatro, GncYawReachesTheBruteForceTlsOptimumOnTinySets) {
  // TLS cost sum_i min(r_i^2, c^2) over the yaw, scanned on a grid of 600,000 angles: its minima
  // are smooth points (a kink of min(r^2, c^2) is concave), so the grid misses them by O(h^2).
  // GNC is a heuristic: most sets, not all, must reach the optimum; none may beat it.
  std::mt19937_64 rng(29);
  std::uniform_real_distribution<double> yaw(-M_PI, M_PI);
  GncSettings s;
  s.noise_bound = 0.1;
  const double c2 = s.noise_bound * s.noise_bound;
  int optimal = 0;
  for (int trial = 0; trial < 50; ++trial) {
    Eigen::Matrix2Xd a, b;
    tiny_tims(8 + trial % 3, 2 + trial % 3, yaw(rng), rng, a, b);
    const YawGncOutcome out = gnc_tls_yaw(a, b, s);
    ASSERT_TRUE(out.gnc.fitted);
    const auto tls = [&](int, double r2) { return std::min(r2, c2); };
    const double grid = scan_yaw(a, b, tls, 600000).second;
    double found = 0.0;
    const Eigen::Matrix2d R = Eigen::Rotation2Dd(out.yaw).toRotationMatrix();
    for (Eigen::Index i = 0; i < a.cols(); ++i)
      found += std::min((b.col(i) - R * a.col(i)).squaredNorm(), c2);
    EXPECT_GE(found, grid - 1e-6 * c2) << "trial " << trial;
    optimal += found <= grid + 1e-6 * c2;
  }
  std::cout << "[ oracle   ] " << optimal << " of 50 at the TLS optimum\n";
  EXPECT_GE(optimal, 45);
}

// ---------------------------------------------------------------------------------------------
// Recovery of drawn motions.

struct Case {
  std::string solver;
  int dim;
  int n;
  double outliers;
  bool planar = false;  ///< 3D: a yaw-only motion (quatro's regime)
  int robin_mode = RobinParams::kMaxCore;
  bool cote_rotation_inliers = false;
};

template <int Dim>
void expect_recovery(const Case& c) {
  const auto solver = SolverRegistry::create(c.solver);
  SolverParams params;
  params.robin.mode = c.robin_mode;
  params.quatro.cote_rotation_inliers = c.cote_rotation_inliers;
  double total_ms = 0.0;
  for (std::uint64_t seed = 1; seed <= 3; ++seed) {
    SyntheticParams p;
    p.n = c.n;
    p.outlier_ratio = c.outliers;
    p.seed = seed;
    p.planar_motion = c.planar;
    const auto set = make_synthetic<Dim>(p);
    const auto start = std::chrono::steady_clock::now();
    const Result<Dim> r = solver->solve(set.corr, params);
    total_ms +=
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    ASSERT_EQ(r.status, Status::ok) << c.solver << " seed " << seed << ": " << r.message;
    EXPECT_LT(rotation_error_deg(r.T_target_source, *set.truth.T_target_source), 1.0) << seed;
    EXPECT_LT(translation_error(r.T_target_source, *set.truth.T_target_source), 0.1) << seed;
    const auto s = inlier_scores(r.inliers, set.truth.labels);
    EXPECT_GT(s.precision, 0.9) << seed;
    EXPECT_GT(s.recall, 0.8) << seed;
    EXPECT_TRUE(std::is_sorted(r.inliers.begin(), r.inliers.end()));
    EXPECT_EQ(std::adjacent_find(r.inliers.begin(), r.inliers.end()), r.inliers.end());
  }
  std::cout << "[ timing   ] " << c.solver << " " << Dim << "D n " << c.n << " outliers "
            << c.outliers << ": " << total_ms / 3 << " ms per solve\n";
}

void expect_recovery(const Case& c) {
  if (c.dim == 2) {
    expect_recovery<2>(c);
  } else {
    expect_recovery<3>(c);
  }
}

// KISS-Matcher's pruning holds at 95% outliers on n = 1000 (at 99%, 10 inliers, the outliers' own
// cores outgrow the inliers' 9-core on these uniform sets: the max core is then outliers).
TEST(RobinGnc, RecoversDrawnMotions3D) { expect_recovery({"robin-gnc", 3, 1000, 0.95}); }
TEST(RobinGnc, RecoversDrawnMotions2D) { expect_recovery({"robin-gnc", 2, 1000, 0.95}); }
TEST(RobinGnc, RecoversDrawnMotionsAtNinetyPercent) {
  expect_recovery({"robin-gnc", 3, 1000, 0.9});
}
TEST(RobinGnc, MaxCliqueModeRecoversDrawnMotions) {
  Case c{"robin-gnc", 3, 1000, 0.99};
  c.robin_mode = RobinParams::kMaxClique;
  expect_recovery(c);
}

// Quatro: yaw-only motions in 3D (the generator's planar_motion: roll = pitch = 0), any planar
// motion in 2D.
TEST(Quatro, RecoversYawOnlyMotions3D) { expect_recovery({"quatro", 3, 1000, 0.95, true}); }
TEST(Quatro, RecoversYawOnlyMotionsAtNinetyNinePercent) {
  expect_recovery({"quatro", 3, 1000, 0.99, true});
}
TEST(Quatro, RecoversPlanarMotions2D) { expect_recovery({"quatro", 2, 1000, 0.95}); }
TEST(Quatro, CoteOnRotationInliersRecoversYawOnlyMotions) {
  Case c{"quatro", 3, 1000, 0.95, true};
  c.cote_rotation_inliers = true;
  expect_recovery(c);
}

TEST(Quatro, YawOnlyMotionsDrawnHereAreRecovered) {
  // The motion drawn here, not by the generator: yaw uniform, translation in a 4 m box, points in
  // a 20 x 20 x 3 m slab (a street), 90% outliers anywhere in it.
  std::mt19937_64 rng(31);
  std::uniform_real_distribution<double> yaw(-M_PI, M_PI), t(-2.0, 2.0), xy(-10.0, 10.0),
      z(-1.5, 1.5);
  std::normal_distribution<double> noise(0.0, 0.01);
  const auto solver = SolverRegistry::create("quatro");
  for (int trial = 0; trial < 3; ++trial) {
    Rigid<3> truth = Rigid<3>::Identity();
    truth.linear() = Eigen::AngleAxisd(yaw(rng), Eigen::Vector3d::UnitZ()).toRotationMatrix();
    truth.translation() << t(rng), t(rng), 0.25 * t(rng);
    const int n = 500;
    Correspondences<3> corr;
    corr.source.resize(3, n);
    corr.target.resize(3, n);
    std::vector<int> truth_inliers;
    for (int i = 0; i < n; ++i) {
      corr.source.col(i) << xy(rng), xy(rng), z(rng);
      if (i % 10 == 0) {
        corr.target.col(i) =
            truth * corr.source.col(i).eval() + Eigen::Vector3d(noise(rng), noise(rng), noise(rng));
        truth_inliers.push_back(i);
      } else {
        corr.target.col(i) << xy(rng), xy(rng), z(rng);
      }
    }
    const Result<3> r = solver->solve(corr, SolverParams{});
    ASSERT_EQ(r.status, Status::ok) << r.message;
    EXPECT_LT(rotation_error_deg(r.T_target_source, truth), 1.0);
    EXPECT_LT(translation_error(r.T_target_source, truth), 0.1);
    std::vector<int> common;
    std::set_intersection(r.inliers.begin(), r.inliers.end(), truth_inliers.begin(),
                          truth_inliers.end(), std::back_inserter(common));
    EXPECT_GT(common.size(), 0.9 * r.inliers.size());
    EXPECT_GT(common.size(), 0.8 * truth_inliers.size());
  }
}

TEST(Quatro, KeepsItsRotationAboutZUnderRoll) {
  // A motion with 10 deg of roll: quatro's rotation is R_z(theta) by definition, so its z axis
  // stays (0, 0, 1) exactly; its yaw is still estimated (close to the true one here).
  std::mt19937_64 rng(37);
  const auto solver = SolverRegistry::create("quatro");
  for (int trial = 0; trial < 3; ++trial) {
    const double true_yaw = std::uniform_real_distribution<double>(-M_PI, M_PI)(rng);
    Rigid<3> truth = Rigid<3>::Identity();
    truth.linear() = (Eigen::AngleAxisd(true_yaw, Eigen::Vector3d::UnitZ()) *
                      Eigen::AngleAxisd(10.0 * M_PI / 180.0, Eigen::Vector3d::UnitX()))
                         .toRotationMatrix();
    truth.translation() << 1.0, -2.0, 0.3;
    SyntheticParams p;
    p.n = 300;
    p.outlier_ratio = 0.5;
    p.seed = 40 + static_cast<std::uint64_t>(trial);
    auto set = make_synthetic<3>(p);
    for (Eigen::Index i = 0; i < set.corr.size(); ++i) {  // re-move the inliers by this motion
      if (set.truth.labels[static_cast<std::size_t>(i)]) {
        set.corr.target.col(i) = truth * set.corr.source.col(i).eval();
      }
    }
    const Result<3> r = solver->solve(set.corr, SolverParams{});
    ASSERT_NE(r.status, Status::error) << r.message;
    const Eigen::Matrix3d R = r.T_target_source.linear();
    EXPECT_NEAR((R.col(2) - Eigen::Vector3d::UnitZ()).norm(), 0.0, 1e-9);
    EXPECT_NEAR((R.row(2) - Eigen::RowVector3d::UnitZ()).norm(), 0.0, 1e-9);
    EXPECT_NEAR(R.determinant(), 1.0, 1e-9);
    const double yaw = std::atan2(R(1, 0), R(0, 0));
    std::cout << "[ roll     ] true yaw " << true_yaw << ", estimated " << yaw << ", "
              << r.inliers.size() << " inliers\n";
  }
}

// ---------------------------------------------------------------------------------------------
// Both: the same answer for any thread count, and their rows registered.

class EachOfTwo : public ::testing::TestWithParam<std::string> {};

TEST_P(EachOfTwo, ResultsDoNotDependOnThreads) {
  const auto solver = SolverRegistry::create(GetParam());
  for (int mode : {RobinParams::kMaxCore, RobinParams::kMaxClique}) {
    SyntheticParams p;
    p.n = 1500;
    p.outlier_ratio = 0.9;
    p.seed = 5;
    const auto set = make_synthetic<3>(p);
    SolverParams one, two;
    one.robin.mode = two.robin.mode = mode;
    one.threads = 1;
    two.threads = 2;
    const Result<3> a = solver->solve(set.corr, one), b = solver->solve(set.corr, two);
    EXPECT_EQ(a.inliers, b.inliers);
    EXPECT_TRUE(a.T_target_source.isApprox(b.T_target_source, 0.0));
    EXPECT_EQ(a.status, b.status);
  }
}

TEST_P(EachOfTwo, RegisteredWithItsRows) {
  bool listed = false;
  for (const auto& info : SolverRegistry::list()) listed |= info.name == GetParam();
  EXPECT_TRUE(listed);
  const std::string option = GetParam() == "quatro" ? "quatro-cote-rotation-inliers" : "robin-mode";
  bool found = false;
  for (const ParamField& f : solver_param_rows()) found |= f.option == option;
  EXPECT_TRUE(found) << option;
}

INSTANTIATE_TEST_SUITE_P(RobinQuatro, EachOfTwo, ::testing::Values("robin-gnc", "quatro"),
                         [](const auto& info) {
                           std::string name = info.param;
                           std::replace(name.begin(), name.end(), '-', '_');
                           return name;
                         });

}  // namespace
}  // namespace verifybench
