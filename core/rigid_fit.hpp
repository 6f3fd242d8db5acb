#pragma once
// Closed-form least-squares rigid fit (Arun et al. 1987; Umeyama 1991, without scale).
#include <optional>
#include <vector>

#include "core/correspondences.hpp"

namespace verifybench {

/// Minimises sum_i w_i ||R m_i + t - q_i||^2 over R in SO(Dim), t in R^Dim, for the listed indices
/// (all correspondences when `indices` is empty is NOT assumed: pass them explicitly).
/// `weights` is empty (all ones) or one non-negative weight per listed index.
/// Reflections are excluded with Umeyama's sign matrix D = diag(1, ..., 1, det(V U^T)), which is
/// right in 2D too (negating a 2x2 R keeps its determinant, so it cannot remove a reflection).
/// Returns nullopt when fewer than 2 points carry weight or the points are degenerate
/// (all coincident, or in 3D all collinear), where the rotation is not determined.
template <int Dim>
std::optional<Rigid<Dim>> fit_rigid(const Correspondences<Dim>& corr,
                                    const std::vector<int>& indices,
                                    const std::vector<double>& weights = {});

/// All correspondences, unweighted.
template <int Dim>
std::optional<Rigid<Dim>> fit_rigid(const Correspondences<Dim>& corr);

}  // namespace verifybench
