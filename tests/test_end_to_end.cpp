// End to end through the harness: clique at 95% outliers, seeds and determinism of sweeps.
#include <gtest/gtest.h>

#include "generators/synthetic.hpp"
#include "harness/builtin.hpp"
#include "harness/harness.hpp"
#include "solvers/registry.hpp"

namespace verifybench {
namespace {

TEST(EndToEnd, CliqueRecoversMotionAt95PercentOutliers) {
  register_builtin_solvers();
  const auto clique = SolverRegistry::create("clique");
  for (std::uint64_t seed = 1; seed <= 10; ++seed) {
    SyntheticParams p;
    p.n = 500;
    p.outlier_ratio = 0.95;
    p.noise = 0.01;
    p.seed = seed;
    const auto set = make_synthetic<3>(p);
    const TrialRecord r = evaluate(*clique, "clique", set, SolverParams{}, AcceptParams{},
                                      SuccessCriteria{});
    EXPECT_EQ(r.status, Status::ok);
    EXPECT_LT(r.rotation_error_deg, 1.0) << "seed " << seed;
    EXPECT_LT(r.translation_error, 0.1) << "seed " << seed;
    EXPECT_GE(r.inlier_recall, 0.9);
  }
}

SweepConfig small_sweep() {
  SweepConfig c;
  c.dims = {2, 3};
  c.n = 80;
  c.outlier_ratios = {0.5, 0.8};
  c.trials = 3;
  c.seed = 5;
  return c;
}

TEST(EndToEnd, SweepIsDeterministicApartFromTimings) {
  register_builtin_solvers();
  const auto a = run_sweep(small_sweep());
  const auto b = run_sweep(small_sweep());
  ASSERT_EQ(a.size(), b.size());
  ASSERT_EQ(a.size(), 2u * 2u * 3u * 2u);
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].data_seed, b[i].data_seed);
    EXPECT_EQ(a[i].inliers, b[i].inliers);
    EXPECT_EQ(a[i].T_target_source, b[i].T_target_source);
  }
}

TEST(EndToEnd, ATrialsSetDoesNotDependOnTheRestOfTheSweep) {
  register_builtin_solvers();
  SweepConfig one = small_sweep();
  one.dims = {3};
  one.outlier_ratios = {0.8};
  const auto full = run_sweep(small_sweep());
  const auto alone = run_sweep(one);
  std::size_t matched = 0;
  for (const auto& r : alone) {
    for (const auto& f : full) {
      if (f.dim == 3 && f.outlier_ratio == 0.8 && f.trial == r.trial && f.solver == r.solver) {
        EXPECT_EQ(f.data_seed, r.data_seed);
        EXPECT_EQ(f.inliers, r.inliers);
        ++matched;
      }
    }
  }
  EXPECT_EQ(matched, alone.size());
}

TEST(EndToEnd, SyntheticSetsHaveTheRequestedComposition) {
  SyntheticParams p;
  p.n = 1000;
  p.outlier_ratio = 0.93;
  const auto set = make_synthetic<2>(p);
  EXPECT_EQ(std::count(set.truth.labels.begin(), set.truth.labels.end(), 1), 70);
  // Inliers obey the drawn motion to within the noise; outliers do not.
  const auto& T = *set.truth.T_target_source;
  for (int i = 0; i < p.n; ++i) {
    const double r = (T * set.corr.source.col(i) - set.corr.target.col(i)).norm();
    if (set.truth.labels[i]) {
      EXPECT_LT(r, 8 * p.noise);
    }
  }
  EXPECT_THROW(make_synthetic<3>(SyntheticParams{0}), std::invalid_argument);
}

}  // namespace
}  // namespace verifybench
