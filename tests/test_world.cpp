// The simulated world, the LiDAR ray caster, the odometry drift model and the trajectory reader,
// against oracles: rays against boxes of known size, a closed room's ranges in closed form,
// zero-noise drift equal to the truth, hand-written pose files.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "core/errors.hpp"
#include "datasets/trajectory.hpp"
#include "generators/lidar.hpp"
#include "generators/odometry.hpp"
#include "generators/world.hpp"
#include "test_util.hpp"

namespace vb = verifybench;
namespace fs = std::filesystem;

namespace {

vb::Rigid<3> pose(double x, double y, double yaw) { return vb::test::planar_pose(x, y, yaw); }

std::vector<vb::Rigid<3>> straight(int n, double step) {
  std::vector<vb::Rigid<3>> path;
  for (int i = 0; i < n; ++i) path.push_back(pose(i * step, 0.0, 0.0));
  return path;
}

#define SKIP_WITHOUT_EMBREE() \
  if (!vb::lidar_available()) GTEST_SKIP() << "built without Embree"

}  // namespace

TEST(Lidar, RayAgainstAKnownBox) {
  SKIP_WITHOUT_EMBREE();
  vb::Mesh mesh;
  mesh.add_box({10.0, 0.0, 0.0}, {1.0, 2.0, 1.5}, 0.0);  // x in [9, 11], y in [-2, 2], z in [0, 3]
  const vb::LidarSimulator lidar(mesh);
  EXPECT_NEAR(lidar.cast({0, 0, 1}, {1, 0, 0}), 9.0, 1e-5);
  EXPECT_NEAR(lidar.cast({0, 1.5, 2.9}, {1, 0, 0}), 9.0, 1e-5);
  EXPECT_NEAR(lidar.cast({10, 0, 10}, {0, 0, -1}), 7.0, 1e-5);  // the top face at z = 3
  EXPECT_TRUE(std::isinf(lidar.cast({0, 0, 1}, {3, 4, 0})));    // passes beside it
  EXPECT_TRUE(std::isinf(lidar.cast({0, 0, 1}, {-1, 0, 0})));
  EXPECT_TRUE(std::isinf(lidar.cast({0, 0, 3.5}, {1, 0, 0})));  // above it
  // Turned by 90 degrees: its long side now lies along x.
  vb::Mesh turned;
  turned.add_box({10.0, 0.0, 0.0}, {1.0, 2.0, 1.5}, M_PI / 2);
  EXPECT_NEAR(vb::LidarSimulator(turned).cast({0, 0, 1}, {1, 0, 0}), 8.0, 1e-5);
}

TEST(Lidar, ScanInsideARoomMatchesClosedForm) {
  SKIP_WITHOUT_EMBREE();
  vb::Mesh room;
  room.add_box({0.0, 0.0, -5.0}, {10.0, 10.0, 5.0}, 0.0);  // walls at |x|, |y| = 10
  vb::LidarParams p;
  p.beams = 1;
  p.fov_down_deg = 0.0;
  p.fov_up_deg = 1.0;  // one beam at elevation fov_down = 0
  p.columns = 360;
  p.range_noise = 0.0;
  p.dropout = 0.0;
  const vb::LidarSimulator lidar(room);
  const auto points = lidar.scan(pose(0, 0, 0.3), p, 7);
  ASSERT_EQ(points.size(), 360u);
  for (std::size_t c = 0; c < points.size(); ++c) {
    const double az = 2.0 * M_PI * c / 360.0;  // sensor frame; the room turned by -0.3 in it
    const double wx = std::cos(az + 0.3), wy = std::sin(az + 0.3);
    const double expected = 10.0 / std::max(std::abs(wx), std::abs(wy));
    EXPECT_NEAR(points[c].cast<double>().norm(), expected, 1e-3) << c;
    EXPECT_NEAR(std::atan2(points[c].y(), points[c].x()), std::atan2(std::sin(az), std::cos(az)),
                1e-4);
  }
  // Noise moves ranges by about its sigma; dropout removes about its share.
  p.range_noise = 0.05;
  p.dropout = 0.2;
  p.columns = 3600;
  const auto noisy = lidar.scan(pose(0, 0, 0), p, 8);
  EXPECT_NEAR(static_cast<double>(noisy.size()) / 3600.0, 0.8, 0.03);
  double sum2 = 0.0;
  for (const auto& q : noisy) {
    const double az = std::atan2(q.y(), q.x());
    const double r = 10.0 / std::max(std::abs(std::cos(az)), std::abs(std::sin(az)));
    sum2 += std::pow(q.cast<double>().norm() - r, 2);
  }
  EXPECT_NEAR(std::sqrt(sum2 / noisy.size()), 0.05, 0.005);
}

TEST(World, SameSeedSameWorldAndScansOtherSeedOther) {
  SKIP_WITHOUT_EMBREE();
  const auto path = straight(200, 1.0);
  vb::WorldParams wp;
  wp.seed = 3;
  const vb::World a = vb::build_street_world(path, wp), b = vb::build_street_world(path, wp);
  ASSERT_EQ(a.mesh.vertices.size(), b.mesh.vertices.size());
  EXPECT_EQ(a.mesh.vertices, b.mesh.vertices);
  EXPECT_EQ(a.counts, b.counts);
  EXPECT_GT(a.counts.at("buildings"), 5);
  wp.seed = 4;
  const vb::World c = vb::build_street_world(path, wp);
  EXPECT_NE(a.mesh.vertices, c.mesh.vertices);
  vb::LidarParams lp;
  lp.columns = 256;
  const vb::LidarSimulator la(a.mesh), lb(b.mesh);
  EXPECT_EQ(la.scan(path[100], lp, 5), lb.scan(path[100], lp, 5));
  EXPECT_NE(la.scan(path[100], lp, 5), la.scan(path[100], lp, 6));
}

TEST(World, RoadIsClearAndGroundUnderTheSensor) {
  SKIP_WITHOUT_EMBREE();
  const auto path = straight(300, 1.0);
  vb::WorldParams wp;
  const vb::World w = vb::build_street_world(path, wp);
  const vb::LidarSimulator lidar(w.mesh);
  for (int i = 20; i < 280; i += 10) {
    const Eigen::Vector3d o = path[i].translation();
    // Straight down: the ground at the sensor height; along the road: nothing within 5 m sideways.
    EXPECT_NEAR(lidar.cast(o, {0, 0, -1}), wp.sensor_height, 1e-3) << i;
    for (double side : {-1.0, 1.0}) {
      EXPECT_GT(lidar.cast(o, {0, side, 0}), wp.road_half_width - 0.5) << i;
    }
  }
}

TEST(Odometry, ZeroNoiseIsTheTruthAndNoiseIsSeeded) {
  std::vector<vb::Rigid<3>> truth;
  for (int i = 0; i < 100; ++i)
    truth.push_back(pose(10 * std::cos(i * 0.05), 10 * std::sin(i * 0.05), i * 0.05 + M_PI / 2));
  vb::DriftParams none{0.0, 0.0, 0.0};
  const auto same = vb::drift_odometry(truth, none, 1);
  for (std::size_t i = 0; i < truth.size(); ++i) {
    EXPECT_TRUE(same[i].isApprox(truth[i], 1e-9)) << i;
  }
  const vb::DriftParams d;
  const auto a = vb::drift_odometry(truth, d, 9), b = vb::drift_odometry(truth, d, 9);
  const auto c = vb::drift_odometry(truth, d, 10);
  EXPECT_TRUE(a.back().isApprox(b.back(), 0.0));
  EXPECT_FALSE(a.back().isApprox(c.back(), 1e-9));
  EXPECT_TRUE(a.front().isApprox(truth.front(), 1e-12));
}

TEST(Odometry, DriftGrowsAsTheModelSays) {
  // Straight 1 km in 1 m steps, translation noise only: the end point's error per axis has
  // sigma trans_rel * sqrt(1000) = 0.316 m; over 400 seeds its rms must be within 15%.
  const auto truth = straight(1001, 1.0);
  vb::DriftParams d{0.01, 0.0, 0.0};
  double sum2 = 0.0;
  for (int s = 0; s < 400; ++s) {
    const auto odo = vb::drift_odometry(truth, d, s);
    sum2 += (odo.back().translation() - truth.back().translation()).squaredNorm() / 3.0;
  }
  EXPECT_NEAR(std::sqrt(sum2 / 400), 0.01 * std::sqrt(1000.0), 0.15 * 0.316);
}

TEST(Trajectory, ReadsKittiPosesAndCalibration) {
  const fs::path dir = fs::temp_directory_path() / "vb_traj";
  fs::create_directories(dir);
  {
    std::ofstream(dir / "poses.txt") << "1 0 0 0 0 1 0 0 0 0 1 0\n\n1 0 0 1.5 0 1 0 2 0 0 1 -3\n";
    std::ofstream(dir / "calib.txt")
        << "P0: 1 2 3\nTr: 0 -1 0 0 0 0 -1 0 1 0 0 0\n";  // velodyne x -> camera z, etc.
  }
  const auto poses = vb::read_kitti_poses((dir / "poses.txt").string());
  ASSERT_EQ(poses.size(), 2u);
  EXPECT_TRUE(poses[1].translation().isApprox(Eigen::Vector3d(1.5, 2, -3)));
  const vb::Rigid<3> Tr = vb::read_kitti_calib_tr((dir / "calib.txt").string());
  const auto velo = vb::camera_to_velodyne(poses, Tr);
  EXPECT_TRUE(velo[0].isApprox(vb::Rigid<3>::Identity(), 1e-12));
  // Camera moves +z (forward) by -3, +x (right) 1.5, +y (down) 2: in Velodyne axes (x forward,
  // y left, z up) that is x = -3, y = -1.5, z = -2.
  EXPECT_TRUE(velo[1].translation().isApprox(Eigen::Vector3d(-3, -1.5, -2), 1e-12))
      << velo[1].translation().transpose();
  vb::write_kitti_poses((dir / "back.txt").string(), velo);
  const auto back = vb::read_kitti_poses((dir / "back.txt").string());
  EXPECT_TRUE(back[1].isApprox(velo[1], 1e-8));
}

TEST(Trajectory, BadFilesNameFileLineAndField) {
  const fs::path dir = fs::temp_directory_path() / "vb_traj_bad";
  fs::create_directories(dir);
  auto expect_error = [&](const std::string& text, const std::string& needle) {
    const std::string path = (dir / "p.txt").string();
    std::ofstream(path) << text;
    try {
      vb::read_kitti_poses(path);
      ADD_FAILURE() << "accepted: " << text;
    } catch (const vb::InputError& e) {
      EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
    }
  };
  expect_error("", "no pose");
  expect_error("1 0 0 0 0 1 0 0 0 0 1\n", ":1: 11 numbers");
  expect_error("1 0 0 0 0 1 0 0 0 0 1 0\n1 0 0 nan 0 1 0 0 0 0 1 0\n", ":2: field 4 'nan'");
  expect_error("2 0 0 0 0 1 0 0 0 0 1 0\n", "p.txt:1");  // not a rotation
  std::ofstream((dir / "c.txt").string()) << "P0: 1 2 3\n";
  EXPECT_THROW(vb::read_kitti_calib_tr((dir / "c.txt").string()), vb::InputError);
  EXPECT_THROW(vb::read_kitti_poses((dir / "missing.txt").string()), vb::InputError);
}

// The drawn block drive: one pose a metre around the rectangle, each lap the same poses.
TEST(World, BlockLapsGoRoundTheRectangleAndRepeat) {
  const auto path = vb::block_laps(30, 20, 2);
  ASSERT_EQ(path.size(), 2u * 100u);  // 2 (30 + 20) m a lap
  auto at = [&](std::size_t k, double x, double y, double yaw) {
    EXPECT_NEAR(path[k].translation().x(), x, 1e-12) << k;
    EXPECT_NEAR(path[k].translation().y(), y, 1e-12) << k;
    EXPECT_NEAR(path[k].translation().z(), 0.0, 1e-12) << k;
    const Eigen::Vector3d heading = path[k].linear().col(0);
    EXPECT_NEAR(heading.x(), std::cos(yaw), 1e-12) << k;
    EXPECT_NEAR(heading.y(), std::sin(yaw), 1e-12) << k;
  };
  at(0, 0, 0, 0);
  at(35, 30, 5, M_PI / 2);
  at(60, 20, 20, M_PI);
  at(95, 0, 5, -M_PI / 2);
  for (std::size_t k = 0; k < 100; ++k) EXPECT_TRUE(path[k].isApprox(path[k + 100], 1e-12)) << k;
}

TEST(World, BlockLapsRefuseSizesThatDrawNoPath) {
  EXPECT_THROW(vb::block_laps(30, 20, 2, 0.0), std::invalid_argument);  // would never end
  EXPECT_THROW(vb::block_laps(-30, 20, 2), std::invalid_argument);
  EXPECT_THROW(vb::block_laps(30, std::nan(""), 2), std::invalid_argument);
  EXPECT_THROW(vb::block_laps(30, 20, -1), std::invalid_argument);
  EXPECT_THROW(vb::block_laps(1e6, 1e6, 10), std::invalid_argument);  // 4e7 poses
  EXPECT_TRUE(vb::block_laps(30, 20, 0).empty());
}
