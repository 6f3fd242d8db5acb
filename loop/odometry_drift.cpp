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

const std::vector<ParamRow<DriftParams>>& drift_param_rows() {
  using P = DriftParams;
  static const std::vector<ParamRow<P>> rows = {
      field_row(&P::trans_rel, "drift-trans", "trans_rel", "F",
                "translation sigma per metre of step", 0.0, 1.0, "a value in [0, 1]"),
      field_row(&P::yaw_deg, "drift-yaw-deg", "yaw_deg_per_sqrt_m", "DEG",
                "yaw random walk [deg / sqrt(m)]", 0.0, 90.0, "a value in [0, 90]"),
      field_row(&P::tilt_deg, "drift-tilt-deg", "tilt_deg_per_sqrt_m", "DEG",
                "roll and pitch random walk [deg / sqrt(m)]", 0.0, 90.0, "a value in [0, 90]")};
  return rows;
}

}  // namespace verifybench
