#pragma once
// Trajectories as KITTI publishes them: one pose a line, the row-major 3x4 [R | t] of the sensor
// in the world frame (T_world_sensor). KITTI odometry's poses.txt are in the left camera's frame;
// a calib.txt `Tr:` line (T_camera_velodyne) turns them into Velodyne poses. And as TUM RGB-D
// publishes them (https://cvg.cit.tum.de/data/datasets/rgbd-dataset/file_formats, read by evo):
// `timestamp tx ty tz qx qy qz qw` a line, the quaternion Hamilton with qw last.
#include <string>
#include <vector>

#include "core/correspondences.hpp"

namespace verifybench {

using Trajectory = std::vector<Rigid<3>>;  ///< T_world_sensor per frame

/// Poses with a time each.
struct StampedTrajectory {
  std::vector<double> stamps;  ///< [s] one per pose, ascending; empty for a KITTI file
  Trajectory poses;
};

/// Reads a KITTI pose file. Throws InputError naming the file, the line and the field for a line
/// that is not 12 finite numbers, a rotation off SO(3) (core/transform.hpp's rule), or no pose.
Trajectory read_kitti_poses(const std::string& path);

/// Twelve tokens as a row-major 3x4 pose, checked as read_kitti_poses checks a line; messages
/// number the fields from `first_field` (2 when a stamp comes first).
Rigid<3> parse_row_major_pose(const std::vector<std::string>& tokens, const std::string& path,
                              long long line, int first_field = 1);

/// Reads a TUM file ('#' comments and blank lines skipped). Throws InputError naming the file, the
/// line, the field and the value for a line that is not 8 finite numbers, a quaternion whose norm
/// is more than 1e-3 from 1 (within it, normalised), a stamp not after the previous one, or for
/// no pose at all.
StampedTrajectory read_tum_poses(const std::string& path);

/// Writes TUM as evo reads it: one pose a line, space-separated, the stamp as %.9f and
/// tx ty tz qx qy qz qw as %.9g (unit quaternion, qw >= 0). std::invalid_argument when the
/// counts differ, std::runtime_error when the file cannot be written.
void write_tum_poses(const std::string& path, const std::vector<double>& stamps,
                     const Trajectory& poses);

/// TUM (8 fields) or KITTI (12) by the field count of the first pose line; InputError for any
/// other count.
StampedTrajectory read_poses_file(const std::string& path);

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
