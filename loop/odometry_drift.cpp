// Odometry "drift": the seeded drift model of generators/odometry.hpp on the true poses of every
// frame (seed derive_seed(config.seed, {3})), and the model's sigmas over a stretch of travel
// (odometry_sigma, which the pose graph weighs every kind's odometry by).
#include <algorithm>
#include <cmath>

#include "core/random.hpp"
#include "loop/odometry.hpp"
#include "loop/sequence.hpp"

namespace verifybench {

Eigen::Matrix<double, 6, 1> odometry_sigma(const DriftParams& d, double length) {
  const double deg = M_PI / 180.0, L = std::max(length, 1.0);
  const double yaw = std::max(d.yaw_deg * deg * std::sqrt(L), 1e-4);
  const double tilt = std::max(d.tilt_deg * deg * std::sqrt(L), 1e-4);
  const double trans = std::max(std::hypot(d.trans_rel * L, yaw * L / std::sqrt(3.0)), 0.05);
  Eigen::Matrix<double, 6, 1> s;
  s << tilt, tilt, yaw, trans, trans, trans;
  return s;
}

OdometryInfo drift_odometry_kind() {
  OdometryInfo info;
  info.name = "drift";
  info.help = "the drift model (--drift-*) on the true poses";
  // config.drift is checked by LoopConfig::validate (every kind's pose graph uses its sigmas).
  info.run = [](const OdometryInput& in) {
    return drift_odometry(in.config.truth, in.config.drift, derive_seed(in.config.seed, {3}));
  };
  return info;
}

}  // namespace verifybench
