#include "frontend/refine.hpp"

#include <pcl/console/print.h>
#include <pcl/registration/gicp.h>

#include <cmath>
#include <stdexcept>
#include <string>

#include "frontend/detail/voxel_grid.hpp"

namespace verifybench {

void RefineParams::validate() const {
  if (!(voxel > 0.0) || !std::isfinite(voxel) || !(max_correspondence > 0.0) ||
      !std::isfinite(max_correspondence) || max_iterations < 1) {
    throw std::invalid_argument("refine: voxel " + std::to_string(voxel) +
                                " and max_correspondence " + std::to_string(max_correspondence) +
                                " must be positive, max_iterations " +
                                std::to_string(max_iterations) + " >= 1");
  }
}

RefineResult refine_icp(const Cloud& source, const Cloud& target, const Rigid<3>& T0,
                        const RefineParams& params) {
  params.validate();
  pcl::console::setVerbosityLevel(pcl::console::L_ALWAYS);
  RefineResult r;
  r.T_target_source = T0;
  Features unused;
  const auto src = detail::voxel_grid(source, params.voxel, unused);
  const auto dst = detail::voxel_grid(target, params.voxel, unused);
  if (src->size() < 20 || dst->size() < 20) return r;  // GICP's covariances need neighbours
  pcl::GeneralizedIterativeClosestPoint<pcl::PointXYZ, pcl::PointXYZ> gicp;
  gicp.setInputSource(src);
  gicp.setInputTarget(dst);
  gicp.setMaxCorrespondenceDistance(params.max_correspondence);
  gicp.setMaximumIterations(params.max_iterations);
  gicp.setTransformationEpsilon(1e-6);
  pcl::PointCloud<pcl::PointXYZ> aligned;
  gicp.align(aligned, T0.matrix().cast<float>());
  if (!gicp.hasConverged()) return r;
  const Eigen::Matrix4d M = gicp.getFinalTransformation().cast<double>();
  r.T_target_source.linear() =
      Eigen::Quaterniond(M.topLeftCorner<3, 3>()).normalized().toRotationMatrix();
  r.T_target_source.translation() = M.topRightCorner<3, 1>();
  r.converged = true;
  r.fitness = gicp.getFitnessScore(params.max_correspondence * params.max_correspondence);
  return r;
}

}  // namespace verifybench
