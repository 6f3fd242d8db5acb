#pragma once
// Point clouds for the extraction pipelines: KITTI .bin (float32 x y z reflectance), .pcd and
// .ply (through PCL's readers), and 4x4 (or 3x4) row-major ground-truth transforms.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "core/correspondences.hpp"

namespace verifybench {

using Cloud = std::vector<Eigen::Vector3f>;

/// By extension (.bin, .pcd, .ply). Throws InputError (core/errors.hpp) naming the
/// file and what is wrong: unreadable, a size that is not whole records, a non-finite coordinate
/// (with its point index), or no points at all.
Cloud read_cloud(const std::string& path);

/// One centroid per occupied cell of a `voxel` grid (PCL's voxel grid filter).
Cloud voxel_downsample(const Cloud& cloud, double voxel);

/// Twelve or sixteen numbers, row-major; the rotation is checked and projected onto SO(3) by the
/// rule of core/transform.hpp.
Rigid<3> read_transform(const std::string& path);

}  // namespace verifybench
