#pragma once
// A seeded odometry drift model: the ground-truth motion between consecutive frames, D_i =
// T_{i-1}^-1 T_i, is perturbed on the right, D'_i = D_i * Exp(w_i, v_i), and the odometry is the
// composition of the perturbed steps from the first true pose. With s_i = |t(D_i)|:
//   v_i ~ N(0, (trans_rel * s_i)^2 I)                  translation, per axis
//   w_z ~ N(0, yaw_deg^2 * s_i)                        yaw, a random walk per metre travelled
//   w_x, w_y ~ N(0, tilt_deg^2 * s_i)                  roll and pitch, likewise
// The defaults (1% translation, 0.05 deg / sqrt(m) yaw) drift like a plain LiDAR odometry:
// tens of metres after a few kilometres, so loop closures matter.
#include <cstdint>
#include <vector>

#include "core/correspondences.hpp"

namespace verifybench {

struct DriftParams {
  double trans_rel = 0.01;  ///< translation sigma per metre of step, per axis
  double yaw_deg = 0.05;    ///< yaw sigma [deg] per sqrt(metre)
  double tilt_deg = 0.005;  ///< roll and pitch sigma [deg] per sqrt(metre)

  /// Throws std::invalid_argument naming the field and value.
  void validate() const;
};

/// Drifted odometry of `truth` (same length, the first pose exact).
std::vector<Rigid<3>> drift_odometry(const std::vector<Rigid<3>>& truth, const DriftParams& params,
                                     std::uint64_t seed);

/// SO(3) x R^3 exponential used above: rotation Exp(w) (angle-axis), translation v.
Rigid<3> perturbation(const Eigen::Vector3d& w, const Eigen::Vector3d& v);

}  // namespace verifybench
