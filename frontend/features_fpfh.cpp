// FPFH front end on PCL 1.13: VoxelGrid, NormalEstimation, FPFHEstimation on every voxel centroid.
// Single-threaded (FPFHEstimation, not the OMP variant), so results do not depend on the machine.
#include <pcl/console/print.h>
#include <pcl/features/fpfh.h>
#include <pcl/features/normal_3d.h>
#include <pcl/point_types.h>
#include <pcl/search/kdtree.h>

#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "core/timer.hpp"
#include "frontend/detail/voxel_grid.hpp"
#include "frontend/features.hpp"

namespace verifybench {

Features features_fpfh(const Cloud& cloud, const PipelineFpfhParams& p) {
  constexpr double kNone = std::numeric_limits<double>::infinity();
  const char* const kMultiple = "the default multiple of the voxel";
  // value, name, what 0 means (nullptr: 0 is invalid), largest valid value
  for (auto [v, name, zero, most] :
       {std::tuple<double, const char*, const char*, double>{p.voxel, "voxel", nullptr, kNone},
        {p.normal_radius, "normal_radius", kMultiple, kNone},
        {p.fpfh_radius, "fpfh_radius", kMultiple, kNone},
        {p.skip_horizontal_deg, "skip_horizontal_deg", "keep every keypoint", 90.0}}) {
    if (std::isfinite(v) && (v > 0.0 || (zero && v == 0.0)) && v <= most) continue;
    std::ostringstream msg;
    msg << "FPFH pipeline: " << name << " = " << v << " is invalid; expected a finite value > 0";
    if (std::isfinite(most)) msg << " and <= " << most;
    if (zero) msg << " (0 = " << zero << ")";
    throw std::invalid_argument(msg.str());
  }
  const double normal_radius = p.normal_radius > 0 ? p.normal_radius : 2.0 * p.voxel;
  const double fpfh_radius = p.fpfh_radius > 0 ? p.fpfh_radius : 5.0 * p.voxel;
  // |n_z| > cos(angle): the normal within `angle` of vertical (either sign: normals are unoriented).
  const double min_vertical = p.skip_horizontal_deg > 0
                                  ? std::cos(p.skip_horizontal_deg * M_PI / 180.0)
                                  : std::numeric_limits<double>::infinity();
  pcl::console::setVerbosityLevel(pcl::console::L_ALWAYS);
  using PointT = pcl::PointXYZ;
  Features f;
  f.dim = 3;
  f.real.dims = 33;
  const pcl::PointCloud<PointT>::Ptr down = detail::voxel_grid(cloud, p.voxel, f);
  f.counts["keypoints"] = static_cast<double>(down->size());

  StopWatch normal_clock;
  pcl::search::KdTree<PointT>::Ptr tree(new pcl::search::KdTree<PointT>);
  pcl::PointCloud<pcl::Normal>::Ptr normals(new pcl::PointCloud<pcl::Normal>);
  pcl::NormalEstimation<PointT, pcl::Normal> ne;
  ne.setInputCloud(down);
  ne.setSearchMethod(tree);
  ne.setRadiusSearch(normal_radius);
  ne.compute(*normals);
  f.ms["normals"] = normal_clock.ms();

  StopWatch fpfh_clock;
  pcl::PointCloud<pcl::FPFHSignature33> fpfh;
  if (!down->empty()) {
    pcl::FPFHEstimation<PointT, pcl::Normal, pcl::FPFHSignature33> est;
    est.setInputCloud(down);
    est.setInputNormals(normals);
    est.setSearchMethod(tree);
    est.setRadiusSearch(fpfh_radius);
    est.compute(fpfh);
  }
  f.ms["fpfh"] = fpfh_clock.ms();
  std::size_t horizontal = 0;
  for (std::size_t k = 0; k < fpfh.size(); ++k) {
    const float* h = fpfh[k].histogram;
    bool ok = std::isfinite((*normals)[k].normal_x);
    for (int j = 0; j < 33 && ok; ++j) ok = std::isfinite(h[j]);
    if (!ok) continue;  // no normal or no support: no descriptor
    if (std::abs((*normals)[k].normal_z) > min_vertical) {
      ++horizontal;
      continue;
    }
    f.real.data.insert(f.real.data.end(), h, h + 33);
    const auto& pt = (*down)[k];
    f.points.emplace_back(pt.x, pt.y, pt.z);
  }
  f.counts["descriptors"] = static_cast<double>(f.points.size());
  f.counts["horizontal_skipped"] = static_cast<double>(horizontal);
  return f;
}

}  // namespace verifybench
