#pragma once
// A spinning multi-beam LiDAR ray-cast into a Mesh with Embree 3 (Debian libembree-dev).
// Sensor model (defaults after the HDL-64E of KITTI):
//   beams        rows spread evenly in elevation from fov_down_deg to fov_up_deg;
//   columns      azimuth steps over 360 degrees, starting at +x, counter-clockwise;
//   range        a return is kept within [min_range, max_range];
//   noise        Gaussian range noise of range_noise (metres, 1 sigma) along the ray;
//   dropout      each return is lost with probability dropout (dark or specular surfaces).
// Points come back in the sensor frame. Every draw is seeded by the caller.
#include <Eigen/Core>
#include <cstdint>
#include <memory>
#include <vector>

#include "core/correspondences.hpp"
#include "core/param_rows.hpp"
#include "generators/world.hpp"

namespace verifybench {

struct LidarParams {
  int beams = 64;
  int columns = 1024;
  double fov_up_deg = 2.0;
  double fov_down_deg = -24.8;
  double min_range = 2.5;    ///< [m] returns of the ego vehicle are cut
  double max_range = 80.0;   ///< [m]
  double range_noise = 0.02; ///< [m] 1 sigma
  double dropout = 0.05;     ///< probability of a lost return

  /// Throws std::invalid_argument naming the field and value.
  void validate() const;
};

/// The LiDAR settings a user sets (`loop --lidar-*`), as rows (core/param_rows.hpp).
const std::vector<ParamRow<LidarParams>>& lidar_param_rows();

/// True when this build ray-casts (VERIFYBENCH_WITH_EMBREE).
bool lidar_available();

class LidarSimulator {
 public:
  /// Builds the Embree scene of `mesh`; throws std::runtime_error in a build without Embree or
  /// when Embree fails.
  explicit LidarSimulator(const Mesh& mesh);
  ~LidarSimulator();
  LidarSimulator(const LidarSimulator&) = delete;
  LidarSimulator& operator=(const LidarSimulator&) = delete;

  /// One sweep from T_world_sensor; seed drives noise and dropouts. Thread-safe.
  std::vector<Eigen::Vector3f> scan(const Rigid<3>& T_world_sensor, const LidarParams& params,
                                    std::uint64_t seed) const;
  /// The distance along one ray (world frame) to the first surface, or +inf.
  double cast(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace verifybench
