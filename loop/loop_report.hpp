#pragma once
// The report of a loop-closure run, in DIR:
//   loop.json  { schema_version, context, parameters, seconds, world, maps, true_closures,
//                closures: [one row per solver x candidate], summary: [one row per solver:
//                solver, pipeline, closures_accepted, tp, fp, fn, precision, recall, f1,
//                max_recall_full_precision, inliers_mean, time_ms_mean, calibration_ms_mean,
//                ape_without_m, ape_with_m, ape_with_robust_m (rmse) and their full statistics],
//                curves: {solver: {count: [...], alpha: [...]}},
//                trajectories: {frames, truth, odometry, <solver>, <solver>+robust: [[x, y, z]...]} }
//   loop.md    the summary in the layout of the paper's Tables I and II
//   trajectories/{reference,odometry,<solver>,<solver>_robust}.tum  every scan used, in the TUM
//              format evo reads as it is (stamp tx ty tz qx qy qz qw): the reference, the
//              odometry (without loops), and each solver's pose graph with its loops, plain and
//              with the robust loss
// Both written atomically (reports/report.hpp); reports/plot_loop.py draws the PNGs from loop.json.
#include <nlohmann/json.hpp>
#include <string>

#include "loop/sequence.hpp"

namespace verifybench {

inline constexpr int kLoopReportSchemaVersion = 1;

nlohmann::json loop_report(const LoopConfig& config, const LoopRun& run,
                           const nlohmann::json& context, const nlohmann::json& parameters);
std::string loop_markdown(const LoopConfig& config, const LoopRun& run);

/// Creates DIR when missing (a non-folder there is refused), writes loop.json and loop.md.
/// Throws std::runtime_error naming the path.
void write_loop_report(const std::string& dir, const nlohmann::json& report,
                       const std::string& markdown);
/// Writes DIR/trajectories/*.tum (the folder is created); stamps are the sequence's, else the
/// frame indices. Throws std::runtime_error naming the path.
void write_loop_trajectories(const std::string& dir, const LoopConfig& config, const LoopRun& run);
/// Checks before the work that DIR is (or can become) a writable folder whose loop.json and
/// loop.md can be written, and that it holds no earlier results: an existing folder must be empty,
/// or, with `overwrite`, a loop output folder (one with loop.json). Throws std::runtime_error
/// naming the path.
void check_loop_dir(const std::string& dir, bool overwrite = false);
/// Empties DIR (--overwrite, after the run and before its results are written), so the folder
/// never mixes two runs' files.
void clear_loop_dir(const std::string& dir);

}  // namespace verifybench
