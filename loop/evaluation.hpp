#pragma once
// What a loop-closure run's rows add up to, per solver, in three of the loop's stages:
//   metrics    the accept decisions scored against the ground truth (TP, FP, FN, precision,
//              recall, F1), the same over the count K and over alpha (score_solvers);
//   back end   the pose graph of the maps with the solver's accepted closures, solved by each back
//              end of loop/backend.hpp, plain and robust (optimise_pose_graphs). Odometry edges
//              carry the drift model's sigmas (odometry_sigma, loop/odometry.hpp): per axis
//              trans_rel * L plus the yaw walk's swing, yaw * sqrt(L) * L / sqrt(3), for maps L
//              apart;
//   metrics    the APE of every scan, without loops and with each back end's, and Kuemmerle's
//              relation error where the sequence has reference relations (trajectory_errors).
#include <vector>

#include "loop/local_maps.hpp"
#include "loop/odometry.hpp"
#include "loop/sequence.hpp"

namespace verifybench {

/// Starts run.summary, one entry per config.solvers: its rows' decisions scored against
/// run.true_closures (score, accepted, means, count and alpha curves).
void score_solvers(const LoopConfig& config, LoopRun& run);

/// For each entry of run.summary: the pose graph of `maps` with odometry edges and the solver's
/// accepted closures as loop edges, solved by the back ends "plain" and "robust"; fills
/// loop_edges, graph_iterations*, graph_converged* and poses_with* (every scan's pose).
void optimise_pose_graphs(const LoopConfig& config, const std::vector<LocalMap>& maps,
                          LoopRun& run);

/// run.ape_without (odometry), and each summary's ape_with and ape_with_robust, against run.truth;
/// with config.relations, the relation errors of the same trajectories (loop/relations.hpp).
void trajectory_errors(const LoopConfig& config, LoopRun& run);

/// The three above in turn: fills run.summary and run.ape_without from run.frames, run.truth,
/// run.odometry, run.rows and run.true_closures.
void summarise_solvers(const LoopConfig& config, const std::vector<LocalMap>& maps, LoopRun& run);

}  // namespace verifybench
