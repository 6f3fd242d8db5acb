#pragma once
// What a loop-closure run is scored by:
//   APE        absolute pose error as evo computes it with -a: the estimated positions aligned to
//              the true ones by the least-squares rigid motion (Umeyama, no scale), then the
//              translation error per pose; rmse, mean, median, max.
//   decisions  accepted closures against the ground truth: TP = accepted and true, FP = accepted
//              and not true, FN = true closures not accepted as TP; precision = TP / (TP + FP)
//              (undefined, NaN, without accepts), recall = TP / (TP + FN), F1.
#include <limits>
#include <vector>

#include "core/correspondences.hpp"

namespace verifybench {

struct ApeStats {
  double rmse = 0, mean = 0, median = 0, max = 0;  ///< [m]
  int poses = 0;
};

/// Throws std::invalid_argument for different lengths or fewer than 3 poses.
ApeStats absolute_pose_error(const std::vector<Rigid<3>>& estimate,
                             const std::vector<Rigid<3>>& truth);

struct ClosureScore {
  static constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  int tp = 0, fp = 0, fn = 0;
  double precision = kNaN, recall = kNaN, f1 = kNaN;
};

/// `accepted[k]` and `correct[k]` per verified candidate; `positives` true closures in all (those
/// never retrieved included). A correct candidate beyond `positives` is a caller's error
/// (std::invalid_argument).
ClosureScore score_closures(const std::vector<bool>& accepted, const std::vector<bool>& correct,
                            int positives);

}  // namespace verifybench
