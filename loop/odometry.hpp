#pragma once
// The loop's odometry stage (issue #29): where each scan used was, as the robot believed it,
// before any loop closure. Each kind is one small file behind the name-keyed registry below
// (core/registry.hpp), chosen by LoopConfig::odometry (--odometry):
//   drift  the seeded drift model of generators/odometry.hpp on the true poses (odometry_drift.cpp)
//   gicp   scan-to-scan GICP on the scans used, frontend/scan_odometry.hpp (odometry_gicp.cpp)
//   poses  LoopConfig::odometry_poses, read from a file, e.g. KISS-ICP's output
//   (odometry_poses.cpp) log    the same, from the recording's own odometry (CARMEN's wheel
//   odometry)
// A new kind is one file defining an OdometryInfo and one line in odometry.cpp's list (or a call
// to register_odometry). Whatever the kind, the pose graph weighs odometry by odometry_sigma().
#include <Eigen/Core>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "datasets/trajectory.hpp"
#include "core/param_rows.hpp"
#include "frontend/scan_odometry.hpp"
#include "generators/odometry.hpp"
#include "loop/local_maps.hpp"

namespace verifybench {

struct LoopConfig;

/// Progress of a kind that works step by step (gicp): steps done, total.
using OdometryStep = std::function<void(long long done, long long total)>;

/// What an odometry kind reads: the run's configuration (config.truth, config.seed and the kind's
/// own fields), the frames used (ascending indices into config.truth) and their scans.
struct OdometryInput {
  const LoopConfig& config;
  const std::vector<int>& frames;
  const ScanSource& scans;
  OdometryStep step;  ///< optional
};

struct OdometryInfo {
  std::string name;
  std::string help;  ///< one line
  /// Checks the kind's own part of the configuration; throws std::invalid_argument naming the
  /// field and value. Optional.
  std::function<void(const LoopConfig& config)> validate;
  /// T_world_sensor for every frame of config.truth (the same length); only the frames used need
  /// be filled in (gicp leaves the others at the identity).
  std::function<Trajectory(const OdometryInput& input)> run;
};

/// The kinds, in the order added: drift, gicp, poses, log.
std::vector<OdometryInfo> list_odometries();
/// The kind `name`. Throws UnknownName (core/registry.hpp, a std::invalid_argument): "unknown
/// odometry 'NAME' (did you mean 'NEAR'?; known: drift, gicp, poses, log)".
const OdometryInfo& find_odometry(const std::string& name);
/// Adds a kind (std::logic_error on a duplicate name).
void register_odometry(OdometryInfo info);

/// Sigmas of the odometry between two poses `length` metres of travel apart under the drift
/// model, (roll, pitch, yaw, x, y, z): the per-axis translation noise adds up to at most
/// trans_rel * L, the yaw walk's sigma is yaw * sqrt(L) and swings the end point sideways by about
/// that times L / sqrt(3). The pose graph's odometry edges, and --odometry-prior's covariance.
Eigen::Matrix<double, 6, 1> odometry_sigma(const DriftParams& d, double length);

// The kinds (one file each).
OdometryInfo drift_odometry_kind();
OdometryInfo gicp_odometry_kind();
/// LoopConfig::odometry_poses as they are, under `name` ("poses", "log").
OdometryInfo poses_odometry_kind(const std::string& name, const std::string& help);

/// The `drift` kind's settings (odometry_drift.cpp; they also weigh the pose graph's odometry edges
/// and a candidate's pose prior) and the `gicp` kind's (odometry_gicp.cpp), as rows.
const std::vector<ParamRow<DriftParams>>& drift_param_rows();
const std::vector<ParamRow<ScanOdometryParams>>& gicp_param_rows();

}  // namespace verifybench
