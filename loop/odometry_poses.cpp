// Odometry "poses" and "log": LoopConfig::odometry_poses as they are, one pose per frame of
// config.truth: read from --odometry-file (e.g. KISS-ICP's output), or the recording's own
// odometry (a CARMEN log's wheel odometry). The two differ only in where the command reads them.
#include <stdexcept>

#include "loop/odometry.hpp"
#include "loop/sequence.hpp"

namespace verifybench {

OdometryInfo poses_odometry_kind(const std::string& name, const std::string& help) {
  OdometryInfo info;
  info.name = name;
  info.help = help;
  info.validate = [](const LoopConfig& config) {
    if (config.odometry_poses.size() != config.truth.size()) {
      throw std::invalid_argument("loop: odometry " + config.odometry + " has " +
                                  std::to_string(config.odometry_poses.size()) + " poses for " +
                                  std::to_string(config.truth.size()) + " frames");
    }
  };
  info.run = [](const OdometryInput& in) { return in.config.odometry_poses; };
  return info;
}

}  // namespace verifybench
