#pragma once
// The loop consistency check (issue #30, intel; Mangelson et al. 2018, "Pairwise Consistent
// Measurement Set Maximization", PCM): a closure decided alone can be a rigid alias, but two
// correct closures must agree through the odometry between their maps. For closures a (query
// qa -> match ma, measured Z_a = T_match_query) and b, the cycle
//   E = O(qa, qb)^-1 * Z_a^-1 * O(ma, mb) * Z_b,  O(i, j) = X_i^-1 X_j (odometry),
// is the identity when both are right. Its d^2 = theta^2 / s_theta^2 + |t|^2 / s_t^2, with the
// drift model's sigmas of both odometry segments (odometry_sigma: yaw and per-axis translation),
// both loop edges' sigmas, and the translation each rotation error swings (its lever arm in E);
// a and b are consistent when d^2 is within the chi-square gate at `confidence` (3 dof in 2D, 6
// in 3D, where the yaw's and the largest axis's sigmas stand for every axis: a wider gate). The
// closures kept are the largest pairwise-consistent set: a maximum clique of the consistency graph,
// found by the project's exact clique search. Per solver, after the accept rule and the dense
// check; 0 = off (the paper's setting).
#include <vector>

#include "core/param_rows.hpp"
#include "core/correspondences.hpp"
#include "loop/local_maps.hpp"
#include "loop/odometry.hpp"

namespace verifybench {

struct ConsistencyParams {
  /// Chi-square confidence of the pairwise gate; 0 = no check.
  double confidence = 0.0;
  /// Throws std::invalid_argument naming the field and value.
  void validate() const;
};

/// The check's settings a user sets (`loop --loop-consistency`), as rows.
const std::vector<ParamRow<ConsistencyParams>>& consistency_param_rows();

/// One accepted closure: the maps and the measured motion (match <- query, lifted to SE(3)).
struct LoopMeasurement {
  int query = 0, match = 0;
  Rigid<3> T_match_query = Rigid<3>::Identity();
};

/// What the check needs of the loop: the drift model and the loop edges' sigmas (the pose graph's).
struct ConsistencyModel {
  DriftParams drift;
  double loop_sigma_trans = 0.5;    ///< [m]
  double loop_sigma_rot_deg = 2.0;  ///< [deg]
  int dim = 3;                      ///< 2: planar (3 dof), 3: 6 dof
};

/// d^2 of the cycle of closures a and b through the maps' odometry poses.
double cycle_d2(const LoopMeasurement& a, const LoopMeasurement& b,
                const std::vector<LocalMap>& maps, const ConsistencyModel& model);

struct ConsistentSet {
  std::vector<int> kept;  ///< indices into the loops, ascending
  bool proven = true;     ///< false: the time limit cut the clique search (its best so far)
};

/// The largest pairwise-consistent set of `loops` (all of them when fewer than two, or when the
/// check is off); `time_limit_s` bounds the clique search.
ConsistentSet consistent_set(const std::vector<LoopMeasurement>& loops,
                                const std::vector<LocalMap>& maps, const ConsistencyModel& model,
                                const ConsistencyParams& params, double time_limit_s);

}  // namespace verifybench
