#pragma once
// The pose prior's gate: a post-fit check with what a loop-closure candidate brings besides its
// correspondences (issue #13). Odometry guesses the motion as T0 with covariance P of the left
// perturbation delta in T = Exp(delta) T0 (core/correspondences.hpp: PosePrior). A motion the
// verifier fits is inside the gate at confidence c when
//     d^2 = delta^T P^-1 delta <= chi2_quantile(c, dof),  delta = Log(T_fit T0^-1),
// dof = 3 in 2D, 6 in 3D. Rigid aliases (two scans that align turned round, or shifted along a
// street) fit motions tens of metres and degrees away from any odometry's guess, which no null
// of the pairing can reject (BENCHMARK.md section 25).
#include <optional>

#include "core/correspondences.hpp"

namespace verifybench {

/// delta = Log(T T0^-1) as the prior's perturbation: (theta, x, y) in 2D, (w, x, y, z) in 3D, w
/// the rotation vector of the rotation part (angle in [0, pi]) and (x, y) / (x, y, z) the
/// translation part, the same split as add_pose_prior() draws.
template <int Dim>
Eigen::Matrix<double, kPoseDof<Dim>, 1> prior_perturbation(const Rigid<Dim>& T,
                                                           const Rigid<Dim>& T0);

/// d^2 of `T` under the prior of `corr`; nullopt when the set has none.
template <int Dim>
std::optional<double> prior_distance2(const Correspondences<Dim>& corr, const Rigid<Dim>& T);

/// Whether d^2 is inside the gate at `confidence` (in (0, 1)) for the dof of SE(Dim).
template <int Dim>
bool inside_prior_gate(double distance2, double confidence);

}  // namespace verifybench
