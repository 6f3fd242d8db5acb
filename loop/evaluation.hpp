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

/// Fills run.summary and run.ape_without from run.frames, run.truth, run.odometry, run.rows and
/// run.true_closures.
void summarise_solvers(const LoopConfig& config, const std::vector<LocalMap>& maps, LoopRun& run);

}  // namespace verifybench
