#pragma once
// An SE(3) pose graph solved with Ceres (Debian libceres-dev): one node a local map, odometry
// edges between consecutive maps and one edge per accepted loop closure. An edge a -> b measures
// T_ab (b's frame into a's); its residual is r = [2 vec(q(E)); t(E)] / sigma with
// E = T_ab^-1 * T_a^-1 * T_b, sigma = (rotation x, y, z [rad], translation x, y, z [m]). The first
// node is held fixed. Optionally a Cauchy loss (scale 1 on the whitened residual) on loop edges:
// the paper uses none, a robust back end shrugs off false loops.
#include <Eigen/Core>
#include <vector>

#include "core/correspondences.hpp"

namespace verifybench {

struct PoseEdge {
  int from = 0, to = 0;
  Rigid<3> T_from_to = Rigid<3>::Identity();
  Eigen::Matrix<double, 6, 1> sigma = Eigen::Matrix<double, 6, 1>::Ones();
  bool loop = false;
};

struct PoseGraphParams {
  bool robust = false;       ///< Cauchy loss on loop edges
  int max_iterations = 100;  ///< Levenberg-Marquardt iterations
};

struct PoseGraphResult {
  std::vector<Rigid<3>> poses;
  double initial_cost = 0, final_cost = 0;
  int iterations = 0;
  bool converged = false;
};

/// Throws std::invalid_argument for an edge naming a missing node or a sigma that is not positive
/// and finite.
PoseGraphResult optimise_pose_graph(const std::vector<Rigid<3>>& initial,
                                    const std::vector<PoseEdge>& edges,
                                    const PoseGraphParams& params);

}  // namespace verifybench
