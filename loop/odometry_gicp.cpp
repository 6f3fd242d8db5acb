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

const std::vector<ParamRow<ScanOdometryParams>>& gicp_param_rows() {
  using P = ScanOdometryParams;
  static const std::vector<ParamRow<P>> rows = {
      field_row(&P::map_scans, "gicp-map-scans", "map_scans", "K",
                "gicp: scans in the local map (1 = scan to scan)", 1, 1000,
                "an integer in [1, 1000]"),
      field_row(&P::voxel, "gicp-voxel", "voxel_m", "M", "gicp: scans downsampled to this voxel",
                0.01, 100.0, "a value in [0.01, 100]"),
      field_row(&P::max_correspondence, "gicp-max-distance", "max_correspondence_m", "M",
                "gicp: correspondence distance", 0.01, 1000.0, "a value in [0.01, 1000]")};
  return rows;
}

}  // namespace verifybench
