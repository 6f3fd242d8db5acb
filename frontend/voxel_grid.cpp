#include "frontend/detail/voxel_grid.hpp"

#include <pcl/filters/voxel_grid.h>

#include "core/timer.hpp"

namespace verifybench::detail {

pcl::PointCloud<pcl::PointXYZ>::Ptr voxel_grid(const Cloud& cloud, double voxel, Features& f) {
  using PointT = pcl::PointXYZ;
  f.counts["points"] = static_cast<double>(cloud.size());
  StopWatch clock;
  pcl::PointCloud<PointT>::Ptr raw(new pcl::PointCloud<PointT>);
  raw->reserve(cloud.size());
  for (const auto& q : cloud) raw->push_back(PointT(q.x(), q.y(), q.z()));
  pcl::PointCloud<PointT>::Ptr down(new pcl::PointCloud<PointT>);
  pcl::VoxelGrid<PointT> grid;
  grid.setInputCloud(raw);
  const auto leaf = static_cast<float>(voxel);
  grid.setLeafSize(leaf, leaf, leaf);
  grid.filter(*down);
  f.ms["voxel"] = clock.ms();
  f.counts["voxels"] = static_cast<double>(down->size());
  return down;
}

}  // namespace verifybench::detail

namespace verifybench {

Cloud voxel_downsample(const Cloud& cloud, double voxel) {
  Features scratch;
  const auto down = detail::voxel_grid(cloud, voxel, scratch);
  Cloud out;
  out.reserve(down->size());
  for (const auto& p : *down) out.emplace_back(p.x, p.y, p.z);
  return out;
}

}  // namespace verifybench
