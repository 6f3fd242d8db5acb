#include "frontend/scan_odometry.hpp"

#include <pcl/console/print.h>
#include <pcl/registration/gicp.h>

#include <cmath>
#include <stdexcept>
#include <string>

#include "frontend/detail/voxel_grid.hpp"

namespace verifybench {

void ScanOdometryParams::validate() const {
  if (!(voxel > 0.0) || !std::isfinite(voxel) || !(max_correspondence > 0.0) ||
      !std::isfinite(max_correspondence) || max_iterations < 1) {
    throw std::invalid_argument(
        "scan odometry: voxel and max_correspondence must be positive and max_iterations >= 1, got " +
        std::to_string(voxel) + ", " + std::to_string(max_correspondence) + ", " +
        std::to_string(max_iterations));
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
  poses.push_back(first);
  Features unused;
  Points::Ptr previous = detail::voxel_grid(scan(0), params.voxel, unused);
  Rigid<3> step = Rigid<3>::Identity();  // T_previous_current, the constant-velocity guess
  for (int k = 1; k < count; ++k) {
    Points::Ptr current = detail::voxel_grid(scan(k), params.voxel, unused);
    if (current->size() >= 20 && previous->size() >= 20) {
      pcl::GeneralizedIterativeClosestPoint<pcl::PointXYZ, pcl::PointXYZ> gicp;
      gicp.setInputSource(current);
      gicp.setInputTarget(previous);
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
    previous = current;
    if (on_step) on_step();
  }
  return poses;
}

}  // namespace verifybench
