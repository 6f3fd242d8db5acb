#pragma once
// A short ICP from a verifier's motion: the dense check of a loop closure where both clouds are at
// hand (KISS-SLAM accepts a closure only when the two local maps still overlap after ICP from the
// fitted motion). PCL's generalized ICP (Segal et al. 2009) on both clouds voxelised at `voxel`.
#include "core/correspondences.hpp"
#include "frontend/cloud_io.hpp"

namespace verifybench {

struct RefineParams {
  double voxel = 0.5;               ///< [m] both clouds downsampled first
  double max_correspondence = 1.0;  ///< [m] GICP correspondence distance
  int max_iterations = 20;
  /// Throws std::invalid_argument naming the field and value.
  void validate() const;
};

struct RefineResult {
  Rigid<3> T_target_source = Rigid<3>::Identity();  ///< refined (the start when not converged)
  bool converged = false;
  double fitness = 0;  ///< PCL's mean squared distance of the matched points [m^2]
};

/// `source` moved into `target`'s frame, starting from T0 (target <- source).
RefineResult refine_icp(const Cloud& source, const Cloud& target, const Rigid<3>& T0,
                        const RefineParams& params);

}  // namespace verifybench
