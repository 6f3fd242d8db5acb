#pragma once
// Accuracy of an estimate against ground truth; NaN marks "undefined" (e.g. precision of an empty
// set).
#include <cstdint>
#include <vector>

#include "core/correspondences.hpp"

namespace verifybench {

/// Geodesic rotation error in degrees: acos((trace(R_gt^T R) - 1) / 2) in 3D, the angle of
/// R_gt^T R in 2D (trace = 2 cos theta); the cosine is clamped to [-1, 1].
template <int Dim>
double rotation_error_deg(const Rigid<Dim>& estimate, const Rigid<Dim>& truth);

/// Euclidean distance between translations.
template <int Dim>
double translation_error(const Rigid<Dim>& estimate, const Rigid<Dim>& truth);

struct InlierScores {
  double precision;  ///< |selected and true| / |selected|; NaN when nothing is selected
  double recall;     ///< |selected and true| / |true|; NaN when there is no true inlier
  double f1;         ///< harmonic mean; NaN when either is NaN, 0 when both are 0
};

/// `labels[i]` is 1 for a true inlier. Throws std::out_of_range for a selected index outside
/// labels.
InlierScores inlier_scores(const std::vector<int>& selected,
                           const std::vector<std::uint8_t>& labels);

/// Geometry of a selected set, for post-fit checks of an accept decision (issue #13).
struct SelectionGeometry {
  /// min(distinct source points, distinct target points) among the selected: an upper bound on
  /// the largest one-to-one subset (k-NN matching repeats sources, radius matching both sides).
  int distinct = 0;
  /// The smallest lever arm a rotation of the selected source points has [m]: in 3D the square
  /// root of the two smallest eigenvalues of their covariance, summed (about 0 for a collinear
  /// set, whose rotation about its line nothing fixes); in 2D the RMS distance to the centroid.
  /// NaN for an empty selection.
  double lever_arm = 0.0;
};

template <int Dim>
SelectionGeometry selection_geometry(const Correspondences<Dim>& corr,
                                     const std::vector<int>& selected);

}  // namespace verifybench
