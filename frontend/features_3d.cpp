// 3D front end on PCL 1.13: VoxelGrid, ISSKeypoint3D, NormalEstimation, SHOTEstimation, then our
// B-SHOT binarisation. Single-threaded so that results do not depend on the machine.
#include <pcl/console/print.h>
#include <pcl/features/normal_3d.h>
#include <pcl/features/shot.h>
#include <pcl/keypoints/iss_3d.h>
#include <pcl/point_types.h>
#include <pcl/search/kdtree.h>

#include <sstream>
#include <stdexcept>

#include "core/timer.hpp"
#include "frontend/bshot.hpp"
#include "frontend/detail/voxel_grid.hpp"
#include "frontend/features.hpp"

namespace verifybench {

namespace {

void require_positive(double v, const char* name) {
  if (v > 0.0 && std::isfinite(v)) return;
  std::ostringstream msg;
  msg << "3D pipeline: " << name << " = " << v << " is invalid; expected a finite value > 0";
  throw std::invalid_argument(msg.str());
}

}  // namespace

Features features_3d(const Cloud& cloud, const Pipeline3dParams& p) {
  for (auto [v, name] : {std::pair{p.voxel, "voxel"},
                         {p.salient_radius, "salient_radius"},
                         {p.non_max_radius, "non_max_radius"},
                         {p.gamma21, "gamma21"},
                         {p.gamma32, "gamma32"},
                         {p.normal_radius, "normal_radius"},
                         {p.shot_radius, "shot_radius"}}) {
    require_positive(v, name);
  }
  pcl::console::setVerbosityLevel(pcl::console::L_ALWAYS);
  using PointT = pcl::PointXYZ;
  Features f;
  f.dim = 3;
  f.descriptors = BinaryDescriptors(kShotLength);
  const pcl::PointCloud<PointT>::Ptr down = detail::voxel_grid(cloud, p.voxel, f);

  StopWatch iss_clock;
  pcl::search::KdTree<PointT>::Ptr tree(new pcl::search::KdTree<PointT>);
  pcl::PointCloud<PointT>::Ptr keypoints(new pcl::PointCloud<PointT>);
  pcl::ISSKeypoint3D<PointT, PointT> iss;
  iss.setSearchMethod(tree);
  iss.setSalientRadius(p.salient_radius);
  iss.setNonMaxRadius(p.non_max_radius);
  iss.setThreshold21(p.gamma21);
  iss.setThreshold32(p.gamma32);
  iss.setMinNeighbors(p.min_neighbors);
  iss.setNumberOfThreads(1);
  iss.setInputCloud(down);
  iss.compute(*keypoints);
  f.ms["iss"] = iss_clock.ms();
  f.counts["keypoints"] = static_cast<double>(keypoints->size());

  StopWatch normal_clock;
  pcl::PointCloud<pcl::Normal>::Ptr normals(new pcl::PointCloud<pcl::Normal>);
  pcl::NormalEstimation<PointT, pcl::Normal> ne;
  ne.setInputCloud(down);
  ne.setSearchMethod(tree);
  ne.setRadiusSearch(p.normal_radius);
  ne.compute(*normals);
  f.ms["normals"] = normal_clock.ms();

  StopWatch shot_clock;
  pcl::PointCloud<pcl::SHOT352> shots;
  if (!keypoints->empty()) {
    pcl::SHOTEstimation<PointT, pcl::Normal, pcl::SHOT352> shot;
    shot.setInputCloud(keypoints);
    shot.setSearchSurface(down);
    shot.setInputNormals(normals);
    shot.setSearchMethod(tree);
    shot.setRadiusSearch(p.shot_radius);
    shot.compute(shots);
  }
  f.ms["shot"] = shot_clock.ms();

  StopWatch bin_clock;
  for (std::size_t k = 0; k < shots.size(); ++k) {
    const float* d = shots[k].descriptor;
    bool finite = true;
    for (int j = 0; j < kShotLength && finite; ++j) finite = std::isfinite(d[j]);
    if (!finite) continue;  // no support (too few neighbours): no descriptor
    binarize_shot(d, f.descriptors.add());
    const auto& kp = (*keypoints)[k];
    f.points.emplace_back(kp.x, kp.y, kp.z);
  }
  f.ms["bshot"] = bin_clock.ms();
  f.counts["descriptors"] = static_cast<double>(f.points.size());
  return f;
}

}  // namespace verifybench
