// The loop consistency check (loop/consistency.hpp) against hand-built cycles and a brute-force
// maximum consistent set.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <random>
#include <vector>

#include "core/chi2.hpp"
#include "loop/consistency.hpp"

namespace vb = verifybench;

namespace {

vb::Rigid<3> pose2d(double x, double y, double yaw_deg) {
  vb::Rigid<3> T = vb::Rigid<3>::Identity();
  T.linear() = Eigen::AngleAxisd(yaw_deg * M_PI / 180.0, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  T.translation() = Eigen::Vector3d(x, y, 0.0);
  return T;
}

/// Maps whose odometry poses are `poses`.
std::vector<vb::LocalMap> maps_at(const std::vector<vb::Rigid<3>>& poses) {
  std::vector<vb::LocalMap> maps(poses.size());
  for (std::size_t i = 0; i < poses.size(); ++i) {
    maps[i].index = static_cast<int>(i);
    maps[i].T_world_map_odometry = poses[i];
  }
  return maps;
}

/// A loop of query -> match measured exactly from the odometry poses, times an error.
vb::LoopMeasurement exact(const std::vector<vb::LocalMap>& maps, int query, int match,
                          const vb::Rigid<3>& error = vb::Rigid<3>::Identity()) {
  return {query, match,
          maps[match].T_world_map_odometry.inverse() * maps[query].T_world_map_odometry * error};
}

vb::ConsistencyModel planar_model() {
  vb::ConsistencyModel m;
  m.drift.trans_rel = 0.1;
  m.drift.yaw_deg = 2.0;
  m.loop_sigma_trans = 0.5;
  m.loop_sigma_rot_deg = 2.0;
  m.dim = 2;
  return m;
}

}  // namespace

TEST(LoopConsistency, TwoExactLoopsCloseTheirCycle) {
  // A square lap of 10 m sides, driven twice: maps 8.. revisit maps 0..
  // The second lap's odometry has drifted (3 m, -2 m, 40 deg), so each loop's motion is far from
  // the identity.
  std::vector<vb::Rigid<3>> poses;
  for (int lap = 0; lap < 2; ++lap) {
    for (int k = 0; k < 8; ++k) {
      const int side = k / 2;
      const double along = (k % 2) * 5.0;
      const double x[] = {along, 10.0, 10.0 - along, 0.0};
      const double y[] = {0.0, along, 10.0, 10.0 - along};
      poses.push_back(pose2d(3.0 * lap, -2.0 * lap, 40.0 * lap) *
                      pose2d(x[side], y[side], 90.0 * side));
    }
  }
  const auto maps = maps_at(poses);
  const auto model = planar_model();
  ASSERT_GT(exact(maps, 9, 1).T_match_query.translation().norm(), 1.0);
  EXPECT_NEAR(vb::cycle_d2(exact(maps, 9, 1), exact(maps, 12, 4), maps, model), 0.0, 1e-18);
  // The same two loops written the other way round (match <- query inverted) do not close it.
  vb::LoopMeasurement inverted = exact(maps, 12, 4);
  inverted.T_match_query = inverted.T_match_query.inverse();
  EXPECT_GT(vb::cycle_d2(exact(maps, 9, 1), inverted, maps, model), vb::chi2_quantile(0.999, 3));
  // One loop off by 90 degrees (a square room's alias): far outside the 3-dof gate.
  const double alias =
      vb::cycle_d2(exact(maps, 9, 1), exact(maps, 12, 4, pose2d(0, 0, 90)), maps, model);
  EXPECT_GT(alias, vb::chi2_quantile(0.999, 3)) << alias;
}

TEST(LoopConsistency, ATranslationOffsetCostsItsSquareOverTheSummedVariances) {
  // Straight line along x, identity rotations: every transform is a translation, so the cycle's
  // translation is the offset itself and its rotation is zero.
  std::vector<vb::Rigid<3>> poses;
  for (int k = 0; k < 6; ++k) poses.push_back(pose2d(10.0 * k, 0.0, 0.0));
  const auto maps = maps_at(poses);
  const auto model = planar_model();
  const vb::LoopMeasurement a{3, 0, pose2d(30.0, 0.0, 0.0)};
  const vb::LoopMeasurement b{5, 1, pose2d(40.0 + 0.7, 0.0, 0.0)};
  // By hand: the queries' segment 3 -> 5 is 20 m, the matches' 0 -> 1 is 10 m; the cycle's
  // translation is -20 - 30 + 10 + 40.7 = 0.7 m. A loop's rotation error swings the rest of the
  // cycle, 10 + 40.7 - 30 = 20.7 m (either way round); the odometry's yaw swings the longer loop,
  // 40.7 m.
  const Eigen::Matrix<double, 6, 1> s_q = vb::odometry_sigma(model.drift, 20.0);
  const Eigen::Matrix<double, 6, 1> s_m = vb::odometry_sigma(model.drift, 10.0);
  const double loop_rot = 2.0 * M_PI / 180.0;
  const double yaw2 = s_q(2) * s_q(2) + s_m(2) * s_m(2);
  const double t_q = std::max(s_q(3), s_q(4)), t_m = std::max(s_m(3), s_m(4));
  const double var_t = t_q * t_q + t_m * t_m + 2.0 * 0.25 + loop_rot * loop_rot * 20.7 * 20.7 +
                       yaw2 * 40.7 * 40.7;
  EXPECT_NEAR(vb::cycle_d2(a, b, maps, model), 0.49 / var_t, 1e-12);
}

TEST(LoopConsistency, KeepsTheLargestConsistentSetAsBruteForceFindsIt) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> xy(-20.0, 20.0), yaw(-180.0, 180.0);
  for (int trial = 0; trial < 20; ++trial) {
    std::vector<vb::Rigid<3>> poses;
    for (int k = 0; k < 30; ++k) poses.push_back(pose2d(xy(rng), xy(rng), yaw(rng)));
    const auto maps = maps_at(poses);
    std::vector<vb::LoopMeasurement> loops;
    std::uniform_int_distribution<int> map(0, 14);
    for (int k = 0; k < 11; ++k) {
      const int q = 15 + map(rng), m = map(rng);
      // Two in three are right (up to 0.1 m and 1 deg), the others a wrong motion.
      const bool right = k % 3 != 2;
      loops.push_back(exact(maps, q, m,
                            right ? pose2d(0.1, 0.0, 1.0) : pose2d(xy(rng), xy(rng), yaw(rng))));
    }
    const auto model = planar_model();
    vb::ConsistencyParams params;
    params.confidence = 0.999;
    const double gate = vb::chi2_quantile(0.999, 3);
    const int n = static_cast<int>(loops.size());
    int best = 0;
    for (int mask = 1; mask < (1 << n); ++mask) {
      bool clique = true;
      for (int i = 0; i < n && clique; ++i) {
        for (int j = i + 1; j < n && clique; ++j) {
          if ((mask >> i & 1) && (mask >> j & 1)) {
            clique = vb::cycle_d2(loops[i], loops[j], maps, model) <= gate;
          }
        }
      }
      if (clique) best = std::max(best, __builtin_popcount(static_cast<unsigned>(mask)));
    }
    const vb::ConsistentSet set = vb::consistent_set(loops, maps, model, params, 10.0);
    EXPECT_TRUE(set.proven);
    const auto& kept = set.kept;
    EXPECT_EQ(static_cast<int>(kept.size()), best) << "trial " << trial;
    for (std::size_t i = 0; i < kept.size(); ++i) {
      for (std::size_t j = i + 1; j < kept.size(); ++j) {
        EXPECT_LE(vb::cycle_d2(loops[kept[i]], loops[kept[j]], maps, model), gate);
      }
    }
    // The right ones agree with each other, so the set is at least as large as they are.
    EXPECT_GE(static_cast<int>(kept.size()), 8) << "trial " << trial;
  }
  vb::ConsistencyParams off;  // 0: every loop kept
  std::vector<vb::LoopMeasurement> two{{1, 0, pose2d(0, 0, 0)}, {2, 0, pose2d(0, 0, 90)}};
  const auto maps = maps_at({pose2d(0, 0, 0), pose2d(1, 0, 0), pose2d(2, 0, 0)});
  EXPECT_EQ(vb::consistent_set(two, maps, planar_model(), off, 1.0).kept,
            (std::vector<int>{0, 1}));
}
