#pragma once
// Trajectories as KITTI publishes them: one pose a line, the row-major 3x4 [R | t] of the sensor
// in the world frame (T_world_sensor). KITTI odometry's poses.txt are in the left camera's frame;
// a calib.txt `Tr:` line (T_camera_velodyne) turns them into Velodyne poses.
#include <string>
#include <vector>

#include "core/correspondences.hpp"

namespace verifybench {

using Trajectory = std::vector<Rigid<3>>;  ///< T_world_sensor per frame

/// Reads a KITTI pose file. Throws InputError naming the file, the line and the field for a line
/// that is not 12 finite numbers, a rotation off SO(3) (core/transform.hpp's rule), or no pose.
Trajectory read_kitti_poses(const std::string& path);

/// The `Tr:` line of a KITTI calib.txt (12 numbers, T_camera_velodyne); InputError when missing.
Rigid<3> read_kitti_calib_tr(const std::string& path);

/// Camera-frame poses to Velodyne-frame poses in a z-up world: the world becomes the first
/// Velodyne frame, T_w'_velo(i) = Tr^-1 * T_cam0_cam(i) * Tr.
Trajectory camera_to_velodyne(const Trajectory& camera_poses, const Rigid<3>& Tr);

/// Writes poses in the KITTI layout (12 numbers a line, 9 significant digits).
void write_kitti_poses(const std::string& path, const Trajectory& poses);

/// Distance travelled up to each frame (0 at the first).
std::vector<double> path_length(const Trajectory& poses);

}  // namespace verifybench
