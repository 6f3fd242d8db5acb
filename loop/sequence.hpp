#pragma once
// Loop closure on a sequence, end to end (the paper's evaluation, issue #14). run_loop is the list
// of its stages (issue #29), each a small function of sequence.cpp over its own interface:
//   sources     scans simulated (a seeded street world along the true trajectory, ray-cast by an
//               HDL-64-like LiDAR) or read from a recorded sequence (loop/sources/, a registry
//               of layouts), one every scan_spacing metres of travel;
//   odometry    a kind of the registry of loop/odometry.hpp: the drift model of
//               generators/odometry.hpp on the true trajectory, scan-to-scan GICP on the scans
//               (frontend/scan_odometry.hpp), or poses given (a file, the recording's own log);
//   local maps  every map_length metres of odometry travel (loop/local_maps.hpp);
//   front end   the 3d (ISS + B-SHOT) or 2d (BEV + ORB) features of each map;
//   truth       a pair is a true closure when its maps are at least min_map_gap apart, their
//               true anchors within gt_max_distance, and their occupancies overlap by more than
//               gt_overlap of the smaller; an accepted closure is correct when the pair is a
//               true closure and the estimated relative pose is within pose_tolerance metres of
//               the truth;
//   retrieval   a retriever of the registry of loop/retrieval.hpp (HBST votes over all older
//               maps, ...);
//   verify      each solver of the registry on the correspondences of each candidate pair
//               (every match within max_hamming bits, as an HBST query returns them), accepted
//               by the solver's rule (count or calibrated p-value), then the dense check when on
//               (acceptance/dense_check.hpp);
//   metrics     per solver, the decisions scored (loop/evaluation.hpp, trajectory_metrics.hpp);
//   back end    per solver, a pose graph of the maps (odometry edges + its accepted closures),
//               solved by each back end of the registry of loop/backend.hpp (plain, robust);
//               APE of every scan's pose with and without loops;
//   report      loop/loop_report.hpp, written by the command from the run.
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "acceptance/accept_params.hpp"
#include "datasets/trajectory.hpp"
#include "frontend/extract.hpp"
#include "frontend/scan_odometry.hpp"
#include "generators/lidar.hpp"
#include "generators/odometry.hpp"
#include "generators/world.hpp"
#include "loop/consistency.hpp"
#include "acceptance/dense_check.hpp"
#include "core/transform.hpp"  // lift_planar
#include "loop/relations.hpp"
#include "loop/local_maps.hpp"
#include "loop/odometry_calibration.hpp"
#include "loop/pose_graph.hpp"
#include "loop/retrieval.hpp"
#include "loop/sources/source.hpp"
#include "loop/trajectory_metrics.hpp"
#include "reports/record.hpp"
#include "solvers/params.hpp"

namespace verifybench {

/// The front end's defaults for local maps: nearest matching within 50 bits, and a bird's-eye
/// image of 80 m half side (ORB skips a 31-pixel border, 15.5 m at 0.5 m cells: a 100 m map seen
/// from its middle needs more than one scan's 50 m).
ExtractParams loop_extract_defaults();

struct LoopConfig {
  Trajectory truth;          ///< T_world_sensor per frame, z up (the excerpt): the reference
  std::string sequence_dir;  ///< empty: simulate; else the recorded sequence's folder or log
  /// The recorded sequence (loop/sources): scan first_frame + i is frame i. Null: simulate.
  std::shared_ptr<const SequenceSource> source;
  int first_frame = 0;       ///< sequence index of truth[0] (file names)
  std::vector<double> stamps;  ///< [s] per frame (the source's; the index when simulated)
  std::string reference = "truth";  ///< where `truth` came from, for the report
  /// odometry "poses" (a file) and "log" (the recording's own): T_world_sensor per frame.
  Trajectory odometry_poses;
  /// Reference relations (loop/relations.hpp; --relations) and the recording's odometry stream
  /// that carries the estimates between frames: the run then reports Kuemmerle's relation error.
  std::vector<Relation> relations;
  std::string relations_file;
  std::vector<double> odometry_stream_stamps;
  Trajectory odometry_stream;
  WorldParams world;
  LidarParams lidar;
  /// "drift": the drift model on the true poses; "gicp": scan-to-scan GICP on the scans used;
  /// "poses": odometry_poses from a file (e.g. KISS-ICP's output); "log": the recording's own
  /// (CARMEN's wheel odometry). The pose graph weighs its steps by the drift model's sigmas.
  std::string odometry = "drift";
  DriftParams drift;
  ScanOdometryParams gicp;
  /// 2D laser logs: the odometry's constant heading drift per metre taken out before the maps
  /// (loop/odometry_calibration.hpp; off by default).
  OdometryCalibrationParams calibration;
  double scan_spacing = 2.0;  ///< [m] travel between the scans used
  LocalMapParams maps;
  RetrievalParams retrieval;
  ExtractParams extract = loop_extract_defaults();  ///< front end and matcher (3d or 2d)
  double gt_overlap = 0.5;        ///< occupancy overlap of a true closure (of the smaller map)
  double gt_max_distance = 100.0; ///< [m] anchors of a true closure at most this far apart
  double pose_tolerance = 6.0;    ///< [m] a correct closure's relative translation error
  std::vector<std::string> solvers{"clique", "ransac"};
  SolverParams params;
  AcceptParams accept;
  double loop_sigma_trans = 0.5;    ///< [m] loop edges in the pose graph
  double loop_sigma_rot_deg = 2.0;  ///< [deg]
  /// Each candidate pair carries odometry's guess of its motion as a pose prior (covariance
  /// odometry_sigma() of the travel between the two maps): the calibrated rule's gate
  /// (acceptance/prior_gate.hpp) and JCBB's prior mode use it. Off: the paper's setting.
  bool odometry_prior = false;
  /// After the accept rule: ICP from the fitted motion and the maps' overlap (off by default).
  DenseCheckParams dense;
  /// After the dense check: the largest pairwise-consistent set of closures per solver (off).
  ConsistencyParams consistency;
  std::uint64_t seed = 1;
  int threads = 1;  ///< maps built in parallel; results do not depend on it

  /// Throws std::invalid_argument naming the field and value.
  void validate() const;
};

/// The loop's own settings a user sets (`loop --scan-spacing`, `--gt-*`, `--pose-tolerance`,
/// `--loop-sigma-*`, `--odometry-prior`), as rows; each stage declares its own beside its params
/// (local_maps.hpp, retrieval.hpp, dense_check.hpp, odometry.hpp, generators' lidar and world).
const std::vector<ParamRow<LoopConfig>>& loop_param_rows();

struct MapInfo {
  int index = 0, first_frame = 0, last_frame = 0, anchor = 0, scans = 0;
  int points = 0, keypoints = 0, occupied_cells = 0;
  Eigen::Vector3d position_truth = Eigen::Vector3d::Zero();
};

struct TrueClosure {
  int query = 0, match = 0;
  double overlap = 0, distance = 0;
};

/// One solver on one candidate pair.
struct ClosureRow {
  int query = 0, match = 0, votes = 0;
  double overlap = 0;       ///< occupancy overlap of the pair
  bool true_closure = false;
  TrialRecord record;       ///< the harness's row: inliers, accepted, times, p-value, ...
  /// match <- query, lifted to SE(3) in 2D: the solver's, or ICP's refinement of it where the
  /// dense check ran (then T_solver holds the solver's); correct and the pose graph use it.
  Rigid<3> T_estimate = Rigid<3>::Identity();
  Rigid<3> T_solver = Rigid<3>::Identity();
  Rigid<3> T_truth = Rigid<3>::Identity();
  double translation_error = 0, rotation_error_deg = 0;  ///< of the solver's motion
  bool correct = false;  ///< true closure and T_estimate within pose_tolerance of the truth
  /// The accept rule's decision; record.accepted is it and the dense check's (when on).
  bool rule_accepted = false;
  DenseCheck dense;  ///< run on every row with a motion when the check is on
  /// The loop consistency check (loop/consistency.hpp), on the closures accepted before it:
  /// whether this one is in the largest consistent set; unset when the check is off or did not
  /// see the row.
  std::optional<bool> consistent;
};

struct CurvePoint {
  double threshold = 0;  ///< min inliers K, or alpha
  ClosureScore score;
};

struct SolverSummary {
  std::string solver;
  ClosureScore score;
  int accepted = 0;
  double inliers_mean = 0, time_ms_mean = 0, calibration_ms_mean = 0;
  std::vector<CurvePoint> count_curve;  ///< accept at inliers >= K, K = 1 .. max + 1
  std::vector<CurvePoint> alpha_curve;  ///< accept at p < alpha (pvalue rule only)
  /// Largest recall over the count curve at precision 1 (0 when no K reaches it).
  double max_recall_full_precision = 0;
  ApeStats ape_with, ape_with_robust;
  RelationError relations_with, relations_with_robust;  ///< with config.relations only
  std::vector<Rigid<3>> poses_with, poses_with_robust;  ///< every scan, optimised
  int loop_edges = 0;
  /// Levenberg-Marquardt iterations of the two pose graphs and whether Ceres reported convergence.
  int graph_iterations = 0, graph_iterations_robust = 0;
  bool graph_converged = false, graph_converged_robust = false;
};

struct LoopRun {
  std::vector<int> frames;  ///< the scans used (indices into config.truth)
  std::vector<Rigid<3>> truth, odometry;  ///< at those frames
  std::vector<MapInfo> maps;
  std::vector<TrueClosure> true_closures;
  std::vector<Candidate> candidates;
  std::vector<ClosureRow> rows;
  std::vector<SolverSummary> summary;
  ApeStats ape_without;
  RelationError relations_without;  ///< the odometry's, with config.relations only
  OdometryCalibration calibration;  ///< ran = false unless --odometry-calibration
  /// The drift model the stages weigh odometry by (pose prior, consistency, pose graph):
  /// config.drift, its yaw sigma the calibration's estimate where that ran.
  DriftParams drift;
  std::map<std::string, double> seconds;  ///< per stage
  std::map<std::string, int> world;       ///< the simulated world's counts
};

/// Progress of the run: stage name, done, total.
using LoopProgress = std::function<void(const std::string& stage, long long done, long long total)>;

/// The whole run. Throws std::invalid_argument (bad configuration), InputError (a scan file).
LoopRun run_loop(const LoopConfig& config, const LoopProgress& progress = {});

/// Every closure row's ground truth on its own: true closures among all map pairs.
std::vector<TrueClosure> true_closures(const std::vector<LocalMap>& maps, int min_map_gap,
                                       double max_distance, double min_overlap);


/// The scans used: the first frame, then each frame once the path from the last one used reaches
/// `spacing`.
std::vector<int> select_frames(const Trajectory& truth, double spacing);

}  // namespace verifybench
