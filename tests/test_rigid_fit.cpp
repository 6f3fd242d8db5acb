// Closed-form rigid fit: recovers drawn transforms; never returns a reflection; is optimal.
#include <gtest/gtest.h>

#include <numeric>

#include "core/metrics.hpp"
#include "core/rigid_fit.hpp"
#include "test_util.hpp"

namespace verifybench {
namespace {

template <int Dim>
Correspondences<Dim> apply(const Rigid<Dim>& T,
                           const Eigen::Matrix<double, Dim, Eigen::Dynamic>& src, double noise,
                           std::mt19937_64& rng) {
  std::normal_distribution<double> g(0.0, noise);
  Correspondences<Dim> c;
  c.source = src;
  c.target = T * src;
  if (noise > 0)
    for (Eigen::Index i = 0; i < c.target.size(); ++i) c.target.data()[i] += g(rng);
  return c;
}

template <int Dim>
double cost(const Correspondences<Dim>& c, const Rigid<Dim>& T) {
  return ((T * c.source) - c.target).squaredNorm();
}

template <class T>
class RigidFit : public ::testing::Test {};
using Dims = ::testing::Types<std::integral_constant<int, 2>, std::integral_constant<int, 3>>;
TYPED_TEST_SUITE(RigidFit, Dims);

TYPED_TEST(RigidFit, RecoversDrawnTransformsExactly) {
  constexpr int Dim = TypeParam::value;
  std::mt19937_64 rng(Dim * 100 + 1);
  for (int rep = 0; rep < 200; ++rep) {
    const Rigid<Dim> T = test::random_rigid<Dim>(rng);
    const Eigen::Matrix<double, Dim, Eigen::Dynamic> src =
        Eigen::Matrix<double, Dim, Eigen::Dynamic>::Random(Dim, 3 + rep % 20) * 10.0;
    const auto c = apply<Dim>(T, src, 0.0, rng);
    const auto est = fit_rigid(c);
    ASSERT_TRUE(est.has_value());
    // acos resolves angles only to ~1e-6 deg near zero; compare the matrices instead.
    EXPECT_LT((est->matrix() - T.matrix()).norm(), 1e-9);
    EXPECT_NEAR(est->linear().determinant(), 1.0, 1e-12);
  }
}

TYPED_TEST(RigidFit, ReverseFitIsTheInverse) {
  constexpr int Dim = TypeParam::value;
  std::mt19937_64 rng(Dim * 100 + 2);
  const Rigid<Dim> T = test::random_rigid<Dim>(rng);
  const auto c =
      apply<Dim>(T, Eigen::Matrix<double, Dim, Eigen::Dynamic>::Random(Dim, 50), 0.05, rng);
  Correspondences<Dim> reversed{c.target, c.source, {}, {}};
  const auto forward = fit_rigid(c);
  const auto backward = fit_rigid(reversed);
  ASSERT_TRUE(forward && backward);
  EXPECT_TRUE(((*forward) * (*backward)).matrix().isIdentity(1e-9));
}

TYPED_TEST(RigidFit, MirroredDataStillGivesAProperRotation) {
  // The reflection trap: target = mirror image of source. The best orthogonal map is a reflection
  // (det -1); the fit must return the best *rotation* instead.
  constexpr int Dim = TypeParam::value;
  std::mt19937_64 rng(Dim * 100 + 3);
  for (int rep = 0; rep < 50; ++rep) {
    Correspondences<Dim> c;
    c.source = Eigen::Matrix<double, Dim, Eigen::Dynamic>::Random(Dim, 12) * 5.0;
    c.target = c.source;
    c.target.row(0) *= -1.0;  // mirror across the first axis
    const auto est = fit_rigid(c);
    ASSERT_TRUE(est.has_value());
    EXPECT_NEAR(est->linear().determinant(), 1.0, 1e-9);
    EXPECT_TRUE((est->linear().transpose() * est->linear()).isIdentity(1e-9));
    // Local optimality oracle: no small rotation (plus the optimal translation) does better.
    const double best = cost(c, *est);
    for (int k = 0; k < 200; ++k) {
      Rigid<Dim> P = *est;
      if constexpr (Dim == 2) {
        P.linear() = Eigen::Rotation2Dd(1e-3 * (k - 100)).toRotationMatrix() * est->linear();
      } else {
        const Eigen::Vector3d axis = Eigen::Vector3d::Random().normalized();
        P.linear() =
            Eigen::AngleAxisd(1e-3 * (k % 20 + 1), axis).toRotationMatrix() * est->linear();
      }
      const auto mean_s = c.source.rowwise().mean();
      const auto mean_t = c.target.rowwise().mean();
      P.translation() = mean_t - P.linear() * mean_s;
      EXPECT_GE(cost(c, P), best - 1e-9);
    }
  }
}

TEST(RigidFit2D, GlobalOptimumAgainstAngleGridSearch) {
  // In 2D the rotation has one parameter: a fine grid over the angle (with the closed-form
  // translation for each angle) is an exact oracle of the optimal cost, reflections included.
  std::mt19937_64 rng(42);
  std::normal_distribution<double> g(0.0, 1.0);
  for (int rep = 0; rep < 40; ++rep) {
    Correspondences<2> c;
    c.source = Eigen::Matrix2Xd::Random(2, 8) * 3.0;
    c.target.resize(2, 8);
    for (int i = 0; i < 8; ++i)
      c.target.col(i) = Eigen::Vector2d(g(rng), g(rng)) * 3.0;  // unrelated
    if (rep % 2) c.target.row(1) = -c.source.row(1);            // exact mirror image
    const auto est = fit_rigid(c);
    ASSERT_TRUE(est.has_value());
    double grid_best = 1e300;
    for (int k = 0; k < 200000; ++k) {
      Rigid<2> P = Rigid<2>::Identity();
      P.linear() = Eigen::Rotation2Dd(2 * M_PI * k / 200000.0).toRotationMatrix();
      P.translation() = c.target.rowwise().mean() - P.linear() * c.source.rowwise().mean();
      grid_best = std::min(grid_best, cost(c, P));
    }
    EXPECT_LE(cost(c, *est), grid_best + 1e-9);
    EXPECT_NEAR(est->linear().determinant(), 1.0, 1e-12);
  }
}

TEST(RigidFit3D, NearlyCollinearPointsStillDetermineTheMotion) {
  std::mt19937_64 rng(9);
  const Rigid<3> T = test::random_rigid<3>(rng);
  Eigen::Matrix3Xd src(3, 6);
  for (int i = 0; i < 6; ++i) src.col(i) = Eigen::Vector3d(i, 2.0 * i, -1.0 * i);
  src(2, 3) += 1e-3;  // one point 1 mm off the line
  const auto c = apply<3>(T, src, 0.0, rng);
  const auto est = fit_rigid(c);
  ASSERT_TRUE(est.has_value());
  EXPECT_LT(rotation_error_deg(*est, T), 1e-4);
}

TEST(RigidFit3D, CollinearOrTooFewPointsAreRefused) {
  Correspondences<3> c;
  c.source = Eigen::Matrix3Xd(3, 4);
  for (int i = 0; i < 4; ++i) c.source.col(i) = Eigen::Vector3d(i, i, i);
  c.target = c.source;
  EXPECT_FALSE(fit_rigid(c).has_value());  // collinear: rotation about the line free
  EXPECT_FALSE(fit_rigid(c, std::vector<int>{0}).has_value());  // one point
  EXPECT_FALSE(fit_rigid(c, std::vector<int>{}).has_value());
}

TEST(PinsMotion, CollinearOrCoincidentSelectionsDoNotPinAMotion) {
  std::mt19937_64 rng(4);
  const Rigid<3> T = test::random_rigid<3>(rng);
  Eigen::Matrix3Xd line(3, 20), plane(3, 20), same(3, 20), bent(3, 6);
  for (int i = 0; i < 20; ++i) {
    line.col(i) = Eigen::Vector3d(1.0 + i, 2.0 + 2.0 * i, -i);
    plane.col(i) = Eigen::Vector3d(i % 5, i / 5, 0.0);  // a planar grid pins a 3D motion
    same.col(i) = Eigen::Vector3d(3, 4, 5);
  }
  for (int i = 0; i < 6; ++i) bent.col(i) = Eigen::Vector3d(i, 2.0 * i, -1.0 * i);
  bent(2, 3) += 1e-3;  // 1 mm off the line: fit_rigid still determines the motion
  std::vector<int> all(20);
  std::iota(all.begin(), all.end(), 0);
  EXPECT_FALSE(pins_motion(apply<3>(T, line, 0.0, rng), all));
  EXPECT_TRUE(pins_motion(apply<3>(T, plane, 0.0, rng), all));
  EXPECT_FALSE(pins_motion(apply<3>(T, same, 0.0, rng), all));
  EXPECT_TRUE(pins_motion(apply<3>(T, bent, 0.0, rng), {0, 1, 2, 3, 4, 5}));
  EXPECT_FALSE(pins_motion(apply<3>(T, plane, 0.0, rng), {0, 1}));  // too few
  // Sources spread but every target the same point: no motion maps them there.
  Correspondences<3> collapsed = apply<3>(T, plane, 0.0, rng);
  collapsed.target.colwise() = Eigen::Vector3d(1, 1, 1);
  EXPECT_FALSE(pins_motion(collapsed, all));
  // 2D: collinear points fix a planar motion, coincident ones do not.
  const Rigid<2> T2 = test::random_rigid<2>(rng);
  Eigen::Matrix2Xd line2(2, 10), same2(2, 10);
  for (int i = 0; i < 10; ++i) line2.col(i) = Eigen::Vector2d(i, 2.0 * i), same2.col(i) = Eigen::Vector2d(7, 7);
  std::vector<int> ten(10);
  std::iota(ten.begin(), ten.end(), 0);
  EXPECT_TRUE(pins_motion(apply<2>(T2, line2, 0.0, rng), ten));
  EXPECT_FALSE(pins_motion(apply<2>(T2, same2, 0.0, rng), ten));
}

TEST(RigidFit, WeightsSelectTheWeightedSubset) {
  std::mt19937_64 rng(13);
  const Rigid<3> T = test::random_rigid<3>(rng);
  Correspondences<3> c = apply<3>(T, Eigen::Matrix3Xd::Random(3, 20) * 4.0, 0.0, rng);
  c.target.rightCols(5).setRandom();  // corrupt the last five
  std::vector<int> all(20);
  std::iota(all.begin(), all.end(), 0);
  std::vector<double> w(20, 1.0);
  std::fill(w.end() - 5, w.end(), 0.0);
  const auto est = fit_rigid(c, all, w);
  ASSERT_TRUE(est.has_value());
  EXPECT_LT((est->matrix() - T.matrix()).norm(), 1e-9);
  EXPECT_THROW(fit_rigid(c, all, std::vector<double>(3, 1.0)), std::invalid_argument);
}

}  // namespace
}  // namespace verifybench
