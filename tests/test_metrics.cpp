// Metrics against values computed by hand.
#include <gtest/gtest.h>

#include <cmath>

#include "core/errors.hpp"
#include "core/metrics.hpp"

namespace verifybench {
namespace {

TEST(Metrics, RotationErrorOfKnownAngles3D) {
  for (double deg : {0.0, 1.0, 30.0, 90.0, 179.0, 180.0}) {
    Rigid<3> a = Rigid<3>::Identity(), b = Rigid<3>::Identity();
    a.linear() = Eigen::AngleAxisd(0.3, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
    b.linear() =
        Eigen::AngleAxisd(deg * M_PI / 180, Eigen::Vector3d(-1, 0, 2).normalized()) * a.linear();
    EXPECT_NEAR(rotation_error_deg<3>(b, a), deg, 1e-5);
  }
}

TEST(Metrics, RotationErrorOfKnownAngles2D) {
  for (double deg : {0.0, 5.0, 90.0, 135.0, 180.0}) {
    Rigid<2> a = Rigid<2>::Identity(), b = Rigid<2>::Identity();
    a.linear() = Eigen::Rotation2Dd(1.0).toRotationMatrix();
    b.linear() = Eigen::Rotation2Dd(1.0 - deg * M_PI / 180).toRotationMatrix();
    EXPECT_NEAR(rotation_error_deg<2>(b, a), deg, 1e-5);
  }
}

TEST(Metrics, TranslationError) {
  Rigid<3> a = Rigid<3>::Identity(), b = Rigid<3>::Identity();
  b.translation() << 3, 4, 0;
  EXPECT_DOUBLE_EQ(translation_error<3>(a, b), 5.0);
}

TEST(Metrics, InlierScoresByHand) {
  const std::vector<std::uint8_t> labels{1, 1, 1, 1, 0, 0, 0, 0};
  const auto s = inlier_scores({0, 1, 4}, labels);  // 2 of 3 right, 2 of 4 found
  EXPECT_DOUBLE_EQ(s.precision, 2.0 / 3.0);
  EXPECT_DOUBLE_EQ(s.recall, 0.5);
  EXPECT_DOUBLE_EQ(s.f1, 2 * (2.0 / 3.0) * 0.5 / (2.0 / 3.0 + 0.5));
  const auto none = inlier_scores({}, labels);
  EXPECT_TRUE(std::isnan(none.precision));
  EXPECT_DOUBLE_EQ(none.recall, 0.0);
  EXPECT_TRUE(std::isnan(none.f1));
  EXPECT_THROW(inlier_scores({8}, labels), std::out_of_range);
}

TEST(Metrics, SelectionGeometryOfKnownShapes) {
  // Points on a line along x (+-5 m), sources repeated twice: the lever arm about that line is 0,
  // only 6 distinct sources. Then a box of half-sides (1, 2, 4) at its 8 corners: covariance
  // diag(1, 4, 16), so the lever is sqrt(1 + 4) = sqrt(5).
  Correspondences<3> c;
  c.source.resize(3, 20);
  c.target.resize(3, 20);
  for (int i = 0; i < 12; ++i) {
    c.source.col(i) = Eigen::Vector3d(-5.0 + 2.0 * (i / 2), 1.0, 2.0);
    c.target.col(i) = Eigen::Vector3d(i, 0, 0);
  }
  for (int k = 0; k < 8; ++k) {
    c.source.col(12 + k) = Eigen::Vector3d(k & 1 ? 1 : -1, k & 2 ? 2 : -2, k & 4 ? 4 : -4);
    c.target.col(12 + k) = Eigen::Vector3d(0, k, 0);
  }
  std::vector<int> line(12), box(8);
  for (int i = 0; i < 12; ++i) line[i] = i;
  for (int k = 0; k < 8; ++k) box[k] = 12 + k;
  const SelectionGeometry l = selection_geometry(c, line);
  EXPECT_EQ(l.distinct, 6);
  EXPECT_NEAR(l.lever_arm, 0.0, 1e-6);
  const SelectionGeometry b = selection_geometry(c, box);
  EXPECT_EQ(b.distinct, 8);
  EXPECT_NEAR(b.lever_arm, std::sqrt(5.0), 1e-12);
  EXPECT_TRUE(std::isnan(selection_geometry(c, {}).lever_arm));
  // 2D: a square of half-side 3 has RMS radius sqrt(18).
  Correspondences<2> s;
  s.source.resize(2, 4);
  s.target = Eigen::Matrix2Xd::Zero(2, 4);
  s.source << 3, -3, 3, -3, 3, 3, -3, -3;
  const SelectionGeometry q = selection_geometry(s, {0, 1, 2, 3});
  EXPECT_NEAR(q.lever_arm, std::sqrt(18.0), 1e-12);
  EXPECT_EQ(q.distinct, 1);  // every target the same point
}

}  // namespace
}  // namespace verifybench

// The one strict number parser every reader and the CLI share.
TEST(NumberTokens, WholeTokensOnlyTinyValuesReadOverflowRefused) {
  using verifybench::NumberError;
  EXPECT_EQ(verifybench::parse_real_token("0.25").value, 0.25);
  EXPECT_EQ(verifybench::parse_real_token("1e-320").error, NumberError::none);  // subnormal
  EXPECT_GT(verifybench::parse_real_token("1e-320").value, 0.0);
  EXPECT_EQ(verifybench::parse_real_token("1e999").error, NumberError::not_finite);
  EXPECT_EQ(verifybench::parse_real_token("nan").error, NumberError::not_finite);
  EXPECT_EQ(verifybench::parse_real_token("1.5x").error, NumberError::not_a_number);
  EXPECT_EQ(verifybench::parse_real_token(" 1").error, NumberError::not_a_number);
  EXPECT_EQ(verifybench::parse_real_token("").error, NumberError::not_a_number);
  EXPECT_EQ(verifybench::parse_integer_token("-42"), -42);
  EXPECT_FALSE(verifybench::parse_integer_token("4294967297x"));
  EXPECT_FALSE(verifybench::parse_integer_token("99999999999999999999"));
  EXPECT_EQ(verifybench::parse_unsigned_token("18446744073709551615"), 18446744073709551615ull);
  EXPECT_FALSE(verifybench::parse_unsigned_token("-1"));
  EXPECT_FALSE(verifybench::parse_unsigned_token("18446744073709551616"));
}
