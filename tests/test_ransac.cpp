// The RANSAC family against oracles: the SVD fit for the minimal closed form, double-precision
// brute force for the scoring kernels, drawn transforms for the solvers, the thread count for
// determinism, and PROSAC's schedule (a perfectly ordered set is solved in the first phase).
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "core/metrics.hpp"
#include "core/rigid_fit.hpp"
#include "generators/synthetic.hpp"
#include "harness/builtin.hpp"
#include "solvers/detail/ransac_kernels.hpp"
#include "solvers/registry.hpp"
#include "test_util.hpp"

namespace verifybench {
namespace {

const char* const kFamily[] = {"ransac", "ransac-adaptive", "msac", "lo-ransac", "prosac"};

template <int Dim>
void minimal_fit_matches_svd(std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> noise(0.0, 0.05);
  for (int trial = 0; trial < 500; ++trial) {
    const Rigid<Dim> T = test::random_rigid<Dim>(rng);
    Eigen::Matrix<double, Dim, Dim> m = 5.0 * Eigen::Matrix<double, Dim, Dim>::Random();
    Eigen::Matrix<double, Dim, Dim> q = (T.linear() * m).colwise() + T.translation();
    for (int k = 0; k < Dim * Dim; ++k) q.data()[k] += noise(rng);  // not an exact fit
    const auto fast = fit_rigid_minimal<Dim>(m, q);
    const auto svd = fit_rigid_fixed<Dim, Dim>(m, q);
    ASSERT_TRUE(fast && svd);
    EXPECT_NEAR((fast->matrix() - svd->matrix()).norm(), 0.0, 1e-8) << "trial " << trial;
    EXPECT_NEAR(fast->linear().determinant(), 1.0, 1e-9);
  }
}

TEST(MinimalFit, MatchesTheSvdFitIn2D) { minimal_fit_matches_svd<2>(1); }
TEST(MinimalFit, MatchesTheSvdFitIn3D) { minimal_fit_matches_svd<3>(2); }

TEST(MinimalFit, RefusesCollinearSamples) {
  Eigen::Matrix3d m;
  m << 0, 1, 2, 0, 1, 2, 0, 1, 2;  // three points on a line
  EXPECT_FALSE(fit_rigid_minimal<3>(m, m));
  Eigen::Matrix2d p = Eigen::Matrix2d::Zero();
  EXPECT_FALSE(fit_rigid_minimal<2>(p, p));
}

/// Brute-force residuals in double; returns false when a residual is too close to the threshold
/// for float and double to be sure to agree.
template <int Dim>
bool oracle_scores(const Correspondences<Dim>& c, const Rigid<Dim>& T, double thr, int& count,
                   double& msac_units) {
  count = 0;
  msac_units = 0.0;
  for (Eigen::Index i = 0; i < c.size(); ++i) {
    const double r2 = (T * c.source.col(i) - c.target.col(i)).squaredNorm();
    if (std::abs(r2 - thr * thr) < 1e-4 * thr * thr) return false;
    count += r2 < thr * thr;
    msac_units += std::min(r2, thr * thr) / (thr * thr) * detail::kMsacUnits;
  }
  return true;
}

template <int Dim>
void kernels_match_brute_force(std::uint64_t seed) {
  SyntheticParams p;
  p.n = 777;  // not a multiple of the block size
  p.outlier_ratio = 0.6;
  p.noise = 0.05;
  p.seed = seed;
  auto set = make_synthetic<Dim>(p);
  set.corr.source.array() += 300.0;  // far from the origin, as KITTI coordinates are
  auto T = *set.truth.T_target_source;
  T.translation() -= T.linear() * Eigen::Matrix<double, Dim, 1>::Constant(300.0);
  const auto pts = detail::make_scoring_points(set.corr);
  std::mt19937_64 rng(seed);
  int checked = 0;
  for (double thr : {0.02, 0.05, 0.1, 0.3}) {
    int count;
    double units;
    if (!oracle_scores(set.corr, T, thr, count, units)) continue;
    ++checked;
    const auto c = detail::centre(pts, T);
    const float t2 = static_cast<float>(thr * thr);
    EXPECT_EQ(detail::count_inliers(pts, c, t2, -1), count) << "thr " << thr;
    // Early exit: exact above the bound, at most the bound otherwise.
    EXPECT_EQ(detail::count_inliers(pts, c, t2, count - 1), count);
    EXPECT_LE(detail::count_inliers(pts, c, t2, count), count);
    EXPECT_LE(detail::count_inliers(pts, c, t2, count + 50), count + 50);
    const std::int64_t cost = detail::msac_cost(pts, c, t2, INT64_MAX);
    EXPECT_NEAR(double(cost), units, p.n + 1e-6 * units);  // truncation: < 1 unit per point
    EXPECT_GE(detail::msac_cost(pts, c, t2, cost / 2), cost / 2);
  }
  EXPECT_GT(checked, 2);
}

TEST(RansacKernels, CountAndMsacMatchBruteForce2D) { kernels_match_brute_force<2>(5); }
TEST(RansacKernels, CountAndMsacMatchBruteForce3D) { kernels_match_brute_force<3>(6); }

class Family : public ::testing::Test {
 protected:
  void SetUp() override { register_builtin_solvers(); }
};

template <int Dim>
void recovers_drawn_motions(const char* name) {
  for (double ratio : {0.5, 0.9}) {
    for (std::uint64_t seed = 1; seed <= 3; ++seed) {
      SyntheticParams p;
      p.n = 400;
      p.outlier_ratio = ratio;
      p.seed = seed;
      const auto set = make_synthetic<Dim>(p);
      SolverParams sp;
      sp.ransac.iterations = 20000;
      sp.seed = seed;
      const auto r = SolverRegistry::create(name)->solve(set.corr, sp);
      ASSERT_TRUE(r.accepted) << name << " ratio " << ratio << " seed " << seed;
      EXPECT_LT(rotation_error_deg(r.T_target_source, *set.truth.T_target_source), 0.5) << name;
      EXPECT_LT(translation_error(r.T_target_source, *set.truth.T_target_source), 0.05) << name;
      const auto q = inlier_scores(r.inliers, set.truth.labels);
      EXPECT_GT(q.recall, 0.95) << name << " ratio " << ratio;
      EXPECT_GT(q.precision, 0.9) << name << " ratio " << ratio;
    }
  }
}

TEST_F(Family, EveryVariantRecoversDrawnMotions2D) {
  for (const char* name : kFamily) recovers_drawn_motions<2>(name);
}
TEST_F(Family, EveryVariantRecoversDrawnMotions3D) {
  for (const char* name : kFamily) recovers_drawn_motions<3>(name);
}

TEST_F(Family, SameResultForAnyThreadCount) {
  SyntheticParams p;
  p.n = 600;
  p.outlier_ratio = 0.95;
  p.seed = 11;
  auto set = make_synthetic<3>(p);
  set.corr.score.resize(static_cast<std::size_t>(p.n));
  std::mt19937_64 rng(3);
  for (double& s : set.corr.score) s = std::uniform_real_distribution<double>(0, 1)(rng);
  for (const char* name : kFamily) {
    SolverParams sp;
    sp.seed = 42;
    sp.threads = 1;
    const auto one = SolverRegistry::create(name)->solve(set.corr, sp);
    for (int threads : {2, 3}) {
      sp.threads = threads;
      const auto many = SolverRegistry::create(name)->solve(set.corr, sp);
      EXPECT_EQ(many.inliers, one.inliers) << name << " threads " << threads;
      EXPECT_EQ(many.counters.iterations, one.counters.iterations) << name;
      EXPECT_TRUE(many.T_target_source.isApprox(one.T_target_source, 0.0)) << name;
    }
  }
}

TEST_F(Family, SameSeedSameDrawsAndAnySeedSolvesEasySets) {
  SyntheticParams p;
  p.n = 300;
  p.outlier_ratio = 0.7;
  const auto set = make_synthetic<3>(p);
  SolverParams a, b;
  a.seed = 1;
  b.seed = 2;
  a.ransac.adaptive = b.ransac.adaptive = true;
  const auto ra = SolverRegistry::create("ransac")->solve(set.corr, a);
  const auto rb = SolverRegistry::create("ransac")->solve(set.corr, b);
  const auto again = SolverRegistry::create("ransac")->solve(set.corr, a);
  EXPECT_EQ(again.inliers, ra.inliers);  // same seed, same draws
  EXPECT_EQ(again.counters.iterations, ra.counters.iterations);
  EXPECT_EQ(inlier_scores(ra.inliers, set.truth.labels).recall, 1.0);
  EXPECT_EQ(inlier_scores(rb.inliers, set.truth.labels).recall, 1.0);
}

TEST_F(Family, ProsacSolvesAPerfectlyOrderedSetInItsFirstPhase) {
  // 97% outliers: uniform sampling needs ~1/0.03^3 = 37,000 draws per all-inlier sample; with
  // the inliers scored highest PROSAC's first samples come from the top of the order.
  SyntheticParams p;
  p.n = 1000;
  p.outlier_ratio = 0.97;
  p.seed = 4;
  auto set = make_synthetic<3>(p);
  set.corr.score.resize(static_cast<std::size_t>(p.n));
  for (std::size_t i = 0; i < set.corr.score.size(); ++i) {
    set.corr.score[i] = set.truth.labels[i] ? 1.0 + 0.001 * double(i) : -double(i);
  }
  SolverParams sp;
  const auto r = SolverRegistry::create("prosac")->solve(set.corr, sp);
  ASSERT_TRUE(r.accepted);
  EXPECT_EQ(inlier_scores(r.inliers, set.truth.labels).recall, 1.0);
  // The adaptive count uses the inlier ratio of the pool (all inliers): a handful of draws.
  EXPECT_LT(r.counters.iterations, 50);
  const auto uniform = SolverRegistry::create("lo-ransac")->solve(set.corr, sp);
  EXPECT_EQ(uniform.counters.iterations, sp.ransac.iterations);  // capped, as theory says
}

TEST_F(Family, FixedCountIsThePapersTenThousand) {
  SyntheticParams p;
  p.n = 200;
  p.outlier_ratio = 0.0;
  const auto set = make_synthetic<3>(p);
  const auto r = SolverRegistry::create("ransac")->solve(set.corr, SolverParams{});
  EXPECT_EQ(r.counters.iterations, 10000);
  EXPECT_EQ(r.counters.local_optimisations, 0);
  const auto lo = SolverRegistry::create("lo-ransac")->solve(set.corr, SolverParams{});
  EXPECT_GE(lo.counters.local_optimisations, 1);
  EXPECT_LT(lo.counters.iterations, 10);  // w = 1 -> k = 0 after the first good sample
}

TEST_F(Family, ScoresOfTheWrongLengthAreAnError) {
  SyntheticParams p;
  p.n = 50;
  auto set = make_synthetic<3>(p);
  set.corr.score.assign(49, 1.0);
  const auto r = SolverRegistry::create("prosac")->solve(set.corr, SolverParams{});
  EXPECT_EQ(r.status, Status::error);
  EXPECT_NE(r.message.find("score count 49"), std::string::npos) << r.message;
  set.corr.score.assign(50, 1.0);
  set.corr.score[7] = std::nan("");
  const auto nan = SolverRegistry::create("prosac")->solve(set.corr, SolverParams{});
  EXPECT_NE(nan.message.find("correspondence 7"), std::string::npos) << nan.message;
}

}  // namespace
}  // namespace verifybench

namespace verifybench {
namespace {

TEST(Family2, TimeLimitStopsTheHypothesisLoop) {
  register_builtin_solvers();
  SyntheticParams p;
  p.n = 2000;
  p.outlier_ratio = 0.99;
  const auto set = make_synthetic<3>(p);
  SolverParams sp;
  sp.ransac.iterations = 100000000;  // ~1 min of work without the limit
  sp.time_limit_s = 0.02;
  for (int threads : {1, 2}) {
    sp.threads = threads;
    const auto r = SolverRegistry::create("ransac")->solve(set.corr, sp);
    EXPECT_EQ(r.status, Status::time_limit) << threads;
    EXPECT_LT(r.counters.iterations, 10000000) << threads;
    EXPECT_GT(r.counters.iterations, 0) << threads;
  }
}

}  // namespace
}  // namespace verifybench
