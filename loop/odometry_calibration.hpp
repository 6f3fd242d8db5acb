#pragma once
// Odometry calibration from the scans (issue #30), after the odometry stage and before the local
// maps. A differential drive whose two wheels differ in effective diameter turns at a constant
// rate per metre it drives (Borenstein and Feng 1996, UMBmark's type B error): its heading error
// grows linearly with travel, which no random walk of the drift model (odometry_sigma()) describes,
// so neither the pose prior's gate nor the loop consistency check can be set for it. A planar
// recording's consecutive scans measure that rate:
//   1. each pair of consecutive scans used (i, i+1) is registered by point-to-line ICP in SE(2)
//      from odometry's motion O_i (scan i+1 into scan i), giving the scan-matched motion Z_i;
//   2. the heading the step's odometry missed is e_i = yaw(Z_i) - yaw(O_i), over its travel
//      L_i = |t(O_i)|;
//   3. the rate is b = sum e_i / sum L_i (the best linear estimate when e_i - b L_i is a random
//      walk, variance proportional to L_i) over the pairs ICP matched, after dropping those whose
//      e_i - b0 L_i lies beyond 3 scaled MADs of the median-based b0;
//   4. the odometry is recomposed with each step's heading change corrected by b L_i:
//        O'_{i+1} = O'_i O_i Rz(b L_i),  O'_0 = O_0;
//   5. what is left, r_i = e_i - b L_i, is the heading's random walk: its sigma per sqrt(metre),
//      q = sqrt(sum r_i^2 / sum L_i) over the kept pairs, replaces the drift model's yaw sigma
//      (--drift-yaw-deg) wherever the loop weighs odometry (pose prior, consistency, pose graph).
//      It holds ICP's own heading error per pair too, so it grows as --scan-spacing shrinks.
// Off by default; 2D laser recordings only (the scans must be planar: carmen).
#include <vector>

#include "core/param_rows.hpp"
#include "datasets/trajectory.hpp"
#include "loop/local_maps.hpp"

namespace verifybench {

struct OdometryCalibrationParams {
  bool enabled = false;       ///< --odometry-calibration
  double max_distance = 0.5;  ///< [m] ICP pairs points closer than this (twice it at first)
  int max_iterations = 30;    ///< ICP iterations per pair of scans
  /// A pair counts as matched when ICP pairs at least this share of the moved scan's points.
  double min_matched_share = 0.5;
  /// Throws std::invalid_argument naming the field and value.
  void validate() const;
};

/// The calibration's settings a user sets (`loop --odometry-calibration`, `--calibration-*`).
const std::vector<ParamRow<OdometryCalibrationParams>>& odometry_calibration_param_rows();

struct OdometryCalibration {
  bool ran = false;
  double yaw_rate_deg_per_m = 0.0;  ///< b, the heading per metre the odometry missed (added back)
  int pairs = 0;                    ///< consecutive scan pairs with travel
  int matched = 0;                  ///< of which ICP matched
  int kept = 0;                     ///< of which inside the MAD trim
  double travel_m = 0.0;            ///< sum L_i over the kept pairs
  /// Root mean square of e_i - b L_i over the kept pairs [deg] (the heading noise left per step).
  double residual_deg_rms = 0.0;
  /// q, the heading's random walk left [deg / sqrt(m)]: the drift model's yaw sigma from here on.
  double yaw_sigma_deg_per_sqrt_m = 0.0;
};

/// Point-to-line ICP in SE(2) of `source` into `target` (x-y of the points) from `T0`; the result
/// and the share of source points paired at the end. Exposed for the tests.
struct PlanarIcp {
  Rigid<2> T = Rigid<2>::Identity();
  double matched_share = 0.0;
  bool converged = false;
};
PlanarIcp planar_icp(const std::vector<Eigen::Vector3f>& source,
                     const std::vector<Eigen::Vector3f>& target, const Rigid<2>& T0,
                     const OdometryCalibrationParams& params);

/// Calibrates `odometry` (T_world_sensor per frame; only `frames` are read and rewritten) from the
/// scans of `frames` as above. Throws std::invalid_argument when a scan is not planar (a point
/// off z = 0, naming the frame) or fewer than 10 pairs are matched or kept (naming the counts).
OdometryCalibration calibrate_odometry(const std::vector<int>& frames, const ScanSource& scans,
                                       const OdometryCalibrationParams& params,
                                       Trajectory& odometry);

}  // namespace verifybench
