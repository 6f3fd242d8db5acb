// The odometry calibration from the scans (loop/odometry_calibration.hpp) against known motions:
// planar ICP on a ray-cast room recovers a known SE(2) motion, and a trajectory whose odometry
// misses a known heading rate per metre gets that rate back and loses its heading drift.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "loop/odometry_calibration.hpp"

namespace vb = verifybench;

namespace {

constexpr double kDeg = M_PI / 180.0;

struct Segment {
  Eigen::Vector2d a, b;
};

/// A 24 x 12 m room with two pillars and an inner wall: enough structure to pin x, y and yaw.
std::vector<Segment> room() {
  auto box = [](double x0, double y0, double x1, double y1) {
    return std::vector<Segment>{{{x0, y0}, {x1, y0}},
                                {{x1, y0}, {x1, y1}},
                                {{x1, y1}, {x0, y1}},
                                {{x0, y1}, {x0, y0}}};
  };
  std::vector<Segment> walls = box(-12, -6, 12, 6);
  for (const auto& pillar : {box(-5, -1, -4, 0.5), box(4, 1, 5.5, 2)}) {
    walls.insert(walls.end(), pillar.begin(), pillar.end());
  }
  walls.push_back({{-1, 3}, {2, 6}});
  return walls;
}

/// A 360-beam laser at `pose` (x, y, yaw), ranges to 20 m: the hits in the sensor frame, z = 0.
std::vector<Eigen::Vector3f> scan_at(const vb::Rigid<2>& pose, const std::vector<Segment>& walls) {
  std::vector<Eigen::Vector3f> points;
  const Eigen::Vector2d o = pose.translation();
  for (int k = 0; k < 360; ++k) {
    const double angle = k * kDeg;
    const Eigen::Vector2d d = pose.linear() * Eigen::Vector2d(std::cos(angle), std::sin(angle));
    double best = 20.0;
    for (const Segment& s : walls) {
      const Eigen::Vector2d e = s.b - s.a;
      const double den = d.x() * (-e.y()) - d.y() * (-e.x());
      if (std::abs(den) < 1e-12) continue;
      const Eigen::Vector2d r = s.a - o;
      const double t = (r.x() * (-e.y()) - r.y() * (-e.x())) / den;
      const double u = (d.x() * r.y() - d.y() * r.x()) / den;
      if (t > 0.05 && u >= 0.0 && u <= 1.0 && t < best) best = t;
    }
    if (best < 20.0) {
      points.emplace_back(static_cast<float>(best * std::cos(angle)),
                          static_cast<float>(best * std::sin(angle)), 0.0f);
    }
  }
  return points;
}

vb::Rigid<2> se2(double x, double y, double yaw_deg) {
  vb::Rigid<2> T = vb::Rigid<2>::Identity();
  T.linear() = Eigen::Rotation2Dd(yaw_deg * kDeg).toRotationMatrix();
  T.translation() = Eigen::Vector2d(x, y);
  return T;
}

vb::Rigid<3> lift(const vb::Rigid<2>& T) {
  vb::Rigid<3> P = vb::Rigid<3>::Identity();
  P.linear().topLeftCorner<2, 2>() = T.linear();
  P.translation().head<2>() = T.translation();
  return P;
}

double yaw_of(const vb::Rigid<3>& T) { return std::atan2(T.linear()(1, 0), T.linear()(0, 0)); }

/// A lap of the room: 0.4 m steps round a rounded rectangle, turning at its corners.
std::vector<vb::Rigid<2>> lap() {
  std::vector<vb::Rigid<2>> poses;
  double x = -8, y = -3.5, yaw = 0;
  for (int side = 0; side < 4; ++side) {
    const int steps = side % 2 == 0 ? 38 : 14;
    for (int i = 0; i < steps; ++i) {
      poses.push_back(se2(x, y, yaw / kDeg));
      x += 0.4 * std::cos(yaw);
      y += 0.4 * std::sin(yaw);
    }
    for (int i = 0; i < 6; ++i) {  // the corner: 90 degrees over 6 steps of 0.3 m
      poses.push_back(se2(x, y, yaw / kDeg));
      yaw += 15 * kDeg;
      x += 0.3 * std::cos(yaw);
      y += 0.3 * std::sin(yaw);
    }
  }
  return poses;
}

}  // namespace

TEST(PlanarIcp, RecoversAKnownMotionFromAPerturbedStart) {
  const auto walls = room();
  const vb::Rigid<2> a = se2(-3, -2, 10), b = se2(-2.4, -1.7, 16);
  const vb::Rigid<2> truth = a.inverse() * b;  // b's scan into a's frame
  const vb::Rigid<2> start = truth * se2(0.15, -0.1, 3);
  const auto icp = vb::planar_icp(scan_at(b, walls), scan_at(a, walls), start, {});
  ASSERT_TRUE(icp.converged);
  EXPECT_GT(icp.matched_share, 0.8);
  EXPECT_LT((icp.T.translation() - truth.translation()).norm(), 0.02);
  EXPECT_LT(std::abs(Eigen::Rotation2Dd(icp.T.linear() * truth.linear().transpose()).angle()),
            0.2 * kDeg);
}

TEST(OdometryCalibration, RecoversAKnownHeadingRateAndTakesTheDriftOut) {
  const auto walls = room();
  const auto truth = lap();
  // Odometry that misses 2.5 deg of heading per metre (it turns right of the truth), plus a
  // seeded random walk of 0.1 deg per step (Box-Muller on mt19937_64: the same draws on every
  // standard library), and six wheel slips of 8 deg that the trim must leave out (kept in, they
  // would move the rate by 6 * 8 deg / 48.5 m = 1 deg / m).
  const double missed = 2.5 * kDeg, step_sigma = 0.1 * kDeg;
  std::mt19937_64 rng(7);
  auto gaussian = [&rng] {
    const double u1 = (static_cast<double>(rng() >> 11) + 1.0) / 9007199254740993.0;
    const double u2 = static_cast<double>(rng() >> 11) / 9007199254740992.0;
    return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * M_PI * u2);
  };
  vb::Trajectory odometry{lift(truth[0])};
  double travel = 0, noise_sq = 0;
  for (std::size_t i = 1; i < truth.size(); ++i) {
    const vb::Rigid<2> step = truth[i - 1].inverse() * truth[i];
    const double L = step.translation().norm();
    travel += L;
    const double noise = step_sigma * gaussian();
    noise_sq += noise * noise;
    const double slip = i % 20 == 10 ? 8.0 * kDeg : 0.0;
    const vb::Rigid<2> wrong = step * se2(0, 0, (-missed * L + noise + slip) / kDeg);
    odometry.push_back(odometry.back() * lift(wrong));
  }
  std::vector<int> frames(truth.size());
  for (std::size_t i = 0; i < frames.size(); ++i) frames[i] = static_cast<int>(i);
  const vb::ScanSource scans = [&](int f) { return scan_at(truth[f], walls); };
  const double before =
      std::abs(std::remainder(yaw_of(odometry.back()) - yaw_of(lift(truth.back())), 2 * M_PI));
  ASSERT_GT(before, 30 * kDeg);  // the drift the calibration must take out (2.5 * 48.5 m - slips)

  const vb::OdometryCalibration cal = vb::calibrate_odometry(frames, scans, {}, odometry);
  EXPECT_TRUE(cal.ran);
  EXPECT_EQ(cal.pairs, static_cast<int>(truth.size()) - 1);
  EXPECT_GT(cal.matched, cal.pairs * 9 / 10);
  EXPECT_LE(cal.kept, cal.matched - 6);  // the slips are out
  EXPECT_GT(cal.kept, cal.matched * 3 / 4);
  // The estimator's own spread: 0.1 deg * sqrt(127 steps) / 48.5 m = 0.023 deg / m.
  EXPECT_NEAR(cal.yaw_rate_deg_per_m, 2.5, 0.1) << "kept " << cal.kept << " of " << cal.matched;
  EXPECT_NEAR(cal.travel_m, travel, 0.15 * travel);  // the slips' steps and no others left out
  // The noise left per sqrt(m): sqrt(sum noise^2 / travel), ICP's own error on top.
  const double q = std::sqrt(noise_sq / travel) / kDeg;
  EXPECT_GT(cal.yaw_sigma_deg_per_sqrt_m, 0.7 * q) << q;
  EXPECT_LT(cal.yaw_sigma_deg_per_sqrt_m, 2.0 * q) << q;
  // The heading the calibrated odometry ends with: the slips and the random walk, no drift.
  const double end = std::remainder(yaw_of(odometry.back()) - yaw_of(lift(truth.back())), 2 * M_PI);
  EXPECT_LT(std::abs(end - 6 * 8.0 * kDeg), 0.1 * kDeg * travel + 4.0 * std::sqrt(noise_sq))
      << end / kDeg;
}

TEST(OdometryCalibration, RefusesScansOffThePlaneAndTooFewMatches) {
  const vb::Trajectory odometry = {lift(se2(0, 0, 0)), lift(se2(1, 0, 0)), lift(se2(2, 0, 0))};
  vb::Trajectory copy = odometry;
  const vb::ScanSource lifted = [](int f) {
    return std::vector<Eigen::Vector3f>{{1, 2, 0}, {3, 1, f == 1 ? 0.5f : 0.0f}, {2, 2, 0}};
  };
  try {
    vb::calibrate_odometry({0, 1, 2}, lifted, {}, copy);
    FAIL() << "a point off z = 0 was taken";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("frame 1"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("z = 0.5"), std::string::npos) << e.what();
  }
  const vb::ScanSource empty = [](int) { return std::vector<Eigen::Vector3f>{}; };
  try {
    vb::calibrate_odometry({0, 1, 2}, empty, {}, copy);
    FAIL() << "a calibration without matches ran";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("matched 0 of 2"), std::string::npos) << e.what();
  }
  vb::OdometryCalibrationParams bad;
  bad.max_distance = -1;
  EXPECT_THROW(bad.validate(), std::invalid_argument);
  bad = {};
  bad.min_matched_share = 0;
  EXPECT_THROW(bad.validate(), std::invalid_argument);
}
