// The library RANSACs (PCL, Open3D) behind our registry: the wrappers must hand them the given
// correspondences and bring back their motion, so on easy sets they recover the drawn motion;
// 2D sets go through the z = 0 embedding, whose reflections are refused.
#include <gtest/gtest.h>

#include <cstdlib>

#include "core/metrics.hpp"
#include "generators/synthetic.hpp"
#include "harness/builtin.hpp"
#include "peers/detail/embed.hpp"
#include "solvers/registry.hpp"

namespace verifybench {
namespace {

template <int Dim>
void recovers(const char* name, double ratio, int iterations = 10000) {
  register_builtin_solvers();
  if (!SolverRegistry::contains(name)) GTEST_SKIP() << name << " is not in this build";
  for (std::uint64_t seed = 1; seed <= 3; ++seed) {
    SyntheticParams sp;
    sp.n = 200;
    sp.outlier_ratio = ratio;
    sp.seed = seed;
    const auto set = make_synthetic<Dim>(sp);
    SolverParams params;
    params.seed = seed;
    params.ransac.iterations = iterations;
    const auto r = SolverRegistry::create(name)->solve(set.corr, params);
    ASSERT_NE(r.status, Status::error) << name << ": " << r.message;
    EXPECT_TRUE(r.accepted) << name << " seed " << seed;
    EXPECT_LT(rotation_error_deg(r.T_target_source, *set.truth.T_target_source), 1.0) << name;
    EXPECT_LT(translation_error(r.T_target_source, *set.truth.T_target_source), 0.1) << name;
    EXPECT_GT(inlier_scores(r.inliers, set.truth.labels).recall, 0.9) << name;
  }
}

TEST(Peers, PclRansacRecoversDrawnMotions) {
  recovers<3>("pcl-ransac", 0.5);
  recovers<2>("pcl-ransac", 0.5);
  recovers<3>("pcl-ransac-default", 0.3);
}

TEST(Peers, PclPrerejectiveRecoversDrawnMotionsWithoutOutliers) {
  // It keeps the lowest mean inlier error, not the largest consensus (see pcl_solvers.cpp), so
  // only an outlier-free set is a fair check of the wrapper alone.
  recovers<3>("pcl-prerejective", 0.0, 300);
  recovers<2>("pcl-prerejective", 0.0, 300);
}

TEST(Peers, Open3dRansacRecoversDrawnMotions) {
  recovers<3>("open3d-ransac", 0.3);
  recovers<2>("open3d-ransac", 0.3);
}

// Each peer runs in a child killed at --time-limit: a limit already past comes back at once as
// time_limit with nothing accepted, and what the library sets process-wide (PCL's prerejective
// seeds std::rand) does not reach the caller.
TEST(Peers, HonourTheTimeLimitAndLeaveProcessStateAlone) {
  register_builtin_solvers();
  SyntheticParams sp;
  sp.n = 300;
  sp.outlier_ratio = 0.5;
  const auto set = make_synthetic<3>(sp);
  int ran = 0;
  for (const char* name : {"pcl-ransac", "pcl-ransac-default", "pcl-prerejective",
                           "pcl-prerejective-default", "open3d-ransac", "open3d-ransac-default"}) {
    if (!SolverRegistry::contains(name)) continue;
    ++ran;
    SolverParams params;
    params.time_limit_s = 1e-9;
    const auto r = SolverRegistry::create(name)->solve(set.corr, params);
    EXPECT_EQ(r.status, Status::time_limit) << name << ": " << r.message;
    EXPECT_FALSE(r.accepted) << name;
    std::srand(42);
    const int expected = std::rand();
    std::srand(42);
    params.time_limit_s = 60;
    const auto done = SolverRegistry::create(name)->solve(set.corr, params);
    EXPECT_NE(done.status, Status::time_limit) << name;
    EXPECT_EQ(std::rand(), expected) << name << " changed std::rand's state";
  }
  if (ran == 0) GTEST_SKIP() << "no library peer in this build";
}

TEST(Peers, AnswersOutOfThePlaneOfA2DSetAreRejections) {
  // A half turn about the x axis keeps z = 0 points in the plane but mirrors them.
  Eigen::Matrix4d flip = Eigen::Matrix4d::Identity();
  flip(1, 1) = flip(2, 2) = -1.0;
  SyntheticParams sp;
  sp.n = 20;
  const auto set = make_synthetic<2>(sp);
  Result<2> r;
  take_library_answer<2>(flip, set.corr, SolverParams{}, "peer", r);
  EXPECT_EQ(r.status, Status::rejected);
  EXPECT_FALSE(r.accepted);
  EXPECT_NE(r.message.find("plane"), std::string::npos);
  // An in-plane rotation comes back as the same 2D motion.
  Eigen::Matrix4d turn = Eigen::Matrix4d::Identity();
  turn.block<2, 2>(0, 0) = Eigen::Rotation2Dd(0.7).toRotationMatrix();
  turn(0, 3) = 1.5;
  const auto T = project<2>(turn);
  ASSERT_TRUE(T);
  EXPECT_NEAR(Eigen::Rotation2Dd(T->linear()).angle(), 0.7, 1e-12);
  EXPECT_NEAR(T->translation()(0), 1.5, 1e-12);
}

}  // namespace
}  // namespace verifybench
