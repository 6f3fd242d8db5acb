#pragma once
// The dense check of a closure (issue #31, item 3): the loop has both local maps, so a fitted
// motion can be tested against the clouds themselves. A short generalized ICP from the motion
// (frontend/refine.hpp), then the overlap of the two maps under the refined motion: the share of
// occupied cells they have in common, of the smaller map, |A n B| / min(|A|, |B|), as the ground
// truth measures it (loop/local_maps.hpp). A rigid alias (a motion that a repetitive part of the
// scene agrees with) leaves the rest of the maps apart; KISS-SLAM accepts a closure only above an
// overlap of 0.4 after ICP. Applied after the accept rule, to either rule; 0 = off.
#include "core/param_rows.hpp"
#include "frontend/refine.hpp"
#include "loop/local_maps.hpp"

namespace verifybench {

struct DenseCheckParams {
  /// Accept a closure only when the maps' overlap after ICP exceeds this; 0 = no check (the
  /// paper's setting).
  double min_overlap = 0.0;
  double cell = 0.5;  ///< [m] centroid cells and the radius of the overlap
  RefineParams icp;   ///< voxel 0.5 m, correspondences within 1 m, 20 iterations
  /// Throws std::invalid_argument naming the field and value.
  void validate() const;
};

/// The dense check's settings a user sets (`loop --dense-*`), as rows.
const std::vector<ParamRow<DenseCheckParams>>& dense_check_param_rows();

struct DenseCheck {
  bool ran = false;
  RefineResult icp;    ///< the refined motion (match <- query)
  double overlap = 0;  ///< of the maps under the refined motion
};

/// The check of `T_match_query` between two maps (their points in their own frames).
DenseCheck dense_check(const LocalMap& query, const LocalMap& match, const Rigid<3>& T_match_query,
                       const DenseCheckParams& params);

}  // namespace verifybench
