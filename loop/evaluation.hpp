#pragma once
// What a loop-closure run's rows add up to, per solver: the accept decisions scored against the
// ground truth (TP, FP, FN, precision, recall, F1), the same over the count K and over alpha, and
// the pose graph of the maps with the solver's accepted closures, solved plainly and with a Cauchy
// loss on loop edges, with the APE of every scan. Odometry edges carry the drift model's sigmas:
// per axis trans_rel * L plus the yaw walk's swing, yaw * sqrt(L) * L / sqrt(3), for maps L apart.
#include <vector>

#include "loop/local_maps.hpp"
#include "loop/sequence.hpp"

namespace verifybench {

/// Sigmas of the odometry between two poses `length` metres of travel apart under the drift
/// model, (roll, pitch, yaw, x, y, z): the per-axis translation noise adds up to at most
/// trans_rel * L, the yaw walk's sigma is yaw * sqrt(L) and swings the end point sideways by about
/// that times L / sqrt(3). The pose graph's odometry edges, and --odometry-prior's covariance.
Eigen::Matrix<double, 6, 1> odometry_sigma(const DriftParams& d, double length);

/// Fills run.summary and run.ape_without from run.frames, run.truth, run.odometry, run.rows and
/// run.true_closures.
void summarise_solvers(const LoopConfig& config, const std::vector<LocalMap>& maps, LoopRun& run);

}  // namespace verifybench
