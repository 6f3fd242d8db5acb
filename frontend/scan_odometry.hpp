#pragma once
// LiDAR odometry from the scans themselves: each scan, voxelised, registered by PCL's generalized
// ICP (Segal et al. 2009) to a local map of the last map_scans scans (scan to map; 1 = scan to
// scan), started from the previous step (constant velocity); the poses are the composition of the
// steps from a given first pose. A real odometry's drift, for loop-closure runs on recorded or
// simulated scans (`loop --odometry gicp`).
#include <functional>
#include <vector>

#include "core/correspondences.hpp"
#include "frontend/cloud_io.hpp"

namespace verifybench {

struct ScanOdometryParams {
  double voxel = 1.0;                ///< [m] scans downsampled before registration
  double max_correspondence = 1.0;   ///< [m] GICP correspondence distance
  int max_iterations = 30;
  /// Scans in the local map registered to: 1 = scan to scan (the default: on KITTI 00's path in
  /// the simulated world a 5-scan map slid 2 m a step along one street, BENCHMARK.md 15).
  int map_scans = 1;
  /// Throws std::invalid_argument naming the field and value.
  void validate() const;
};

/// T_world_scan for each of `count` scans (scan(k) gives scan k in its sensor frame), the first at
/// `first`. `on_step` (optional) is called after each registration.
std::vector<Rigid<3>> gicp_odometry(const std::function<Cloud(int k)>& scan, int count,
                                    const Rigid<3>& first, const ScanOdometryParams& params,
                                    const std::function<void()>& on_step = {});

}  // namespace verifybench
