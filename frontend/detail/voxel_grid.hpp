#pragma once
// The first stage of both PCL pipelines (3D, FPFH): the scan through PCL's VoxelGrid.
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include "frontend/features.hpp"

namespace verifybench::detail {

/// The voxel centroids of `cloud` at leaf `voxel`; records counts points / voxels and ms voxel.
pcl::PointCloud<pcl::PointXYZ>::Ptr voxel_grid(const Cloud& cloud, double voxel, Features& f);

}  // namespace verifybench::detail
