#include "frontend/scan_odometry.hpp"

#include <pcl/console/print.h>
#include <pcl/registration/gicp.h>

#include <cmath>
#include <deque>
#include <stdexcept>
#include <string>

#include "frontend/detail/voxel_grid.hpp"

namespace verifybench {

void ScanOdometryParams::validate() const {
  if (!(voxel > 0.0) || !std::isfinite(voxel) || !(max_correspondence > 0.0) ||
      !std::isfinite(max_correspondence) || max_iterations < 1 || map_scans < 1) {
    throw std::invalid_argument(
        "scan odometry: voxel and max_correspondence must be positive, max_iterations and "
        "map_scans >= 1, got " +
        std::to_string(voxel) + ", " + std::to_string(max_correspondence) + ", " +
        std::to_string(max_iterations) + ", " + std::to_string(map_scans));
  }
}

std::vector<Rigid<3>> gicp_odometry(const std::function<Cloud(int k)>& scan, int count,
                                    const Rigid<3>& first, const ScanOdometryParams& params,
                                    const std::function<void()>& on_step) {
  params.validate();
  pcl::console::setVerbosityLevel(pcl::console::L_ALWAYS);
  using Points = pcl::PointCloud<pcl::PointXYZ>;
  std::vector<Rigid<3>> poses;
  if (count <= 0) return poses;
  Features unused;
  // The last map_scans scans, downsampled, each in its own frame (their poses are in `poses`).
  std::deque<std::pair<int, Cloud>> recent;
  auto downsampled = [&](int k) {
    const Points::Ptr p = detail::voxel_grid(scan(k), params.voxel, unused);
    Cloud c;
    c.reserve(p->size());
    for (const auto& q : *p) c.emplace_back(q.x, q.y, q.z);
    return c;
  };
  poses.push_back(first);
  recent.emplace_back(0, downsampled(0));
  Rigid<3> step = Rigid<3>::Identity();  // T_previous_current, the constant-velocity guess
  for (int k = 1; k < count; ++k) {
    Cloud current = downsampled(k);
    // The local map in the previous scan's frame: the recent scans moved there, voxelised again.
    const Rigid<3> T_prev_world = poses.back().inverse();
    Cloud local;
    for (const auto& [j, c] : recent) {
      const Eigen::Matrix4f M = (T_prev_world * poses[j]).matrix().cast<float>();
      for (const auto& q : c) local.push_back(M.topLeftCorner<3, 3>() * q + M.topRightCorner<3, 1>());
    }
    const Points::Ptr target = detail::voxel_grid(local, params.voxel, unused);
    Points::Ptr source(new Points);
    for (const auto& q : current) source->push_back(pcl::PointXYZ(q.x(), q.y(), q.z()));
    if (source->size() >= 20 && target->size() >= 20) {
      pcl::GeneralizedIterativeClosestPoint<pcl::PointXYZ, pcl::PointXYZ> gicp;
      gicp.setInputSource(source);
      gicp.setInputTarget(target);
      gicp.setMaxCorrespondenceDistance(params.max_correspondence);
      gicp.setMaximumIterations(params.max_iterations);
      gicp.setTransformationEpsilon(1e-6);
      Points aligned;
      gicp.align(aligned, step.matrix().cast<float>());
      if (gicp.hasConverged()) {
        Eigen::Matrix4d M = gicp.getFinalTransformation().cast<double>();
        Rigid<3> T = Rigid<3>::Identity();
        T.linear() = Eigen::Quaterniond(M.topLeftCorner<3, 3>()).normalized().toRotationMatrix();
        T.translation() = M.topRightCorner<3, 1>();
        step = T;
      }  // else: keep the constant-velocity guess for this step
    }
    poses.push_back(poses.back() * step);
    recent.emplace_back(k, std::move(current));
    while (static_cast<int>(recent.size()) > params.map_scans) recent.pop_front();
    if (on_step) on_step();
  }
  return poses;
}

}  // namespace verifybench
