// Odometry "gicp": scan-to-scan GICP on the scans used (frontend/scan_odometry.hpp), sequential
// (each step starts from the last), from the true pose of the first frame used. Only the frames
// used are filled in; the others stay at the identity.
#include "frontend/scan_odometry.hpp"
#include "loop/odometry.hpp"
#include "loop/sequence.hpp"

namespace verifybench {

OdometryInfo gicp_odometry_kind() {
  OdometryInfo info;
  info.name = "gicp";
  info.help = "scan-to-scan GICP on the scans used (--gicp-*)";
  info.validate = [](const LoopConfig& config) { config.gicp.validate(); };
  info.run = [](const OdometryInput& in) {
    const Trajectory& truth = in.config.truth;
    Trajectory odometry_all(truth.size(), Rigid<3>::Identity());
    const int n = static_cast<int>(in.frames.size());
    long long steps = 0;
    const auto poses = gicp_odometry([&](int k) { return in.scans(in.frames[k]); }, n,
                                     truth[in.frames[0]], in.config.gicp,
                                     [&] {
                                       ++steps;
                                       if (in.step) in.step(steps, n - 1);
                                     });
    for (int k = 0; k < n; ++k) odometry_all[in.frames[k]] = poses[k];
    return odometry_all;
  };
  return info;
}

}  // namespace verifybench
