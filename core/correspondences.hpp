#pragma once
// Correspondence sets (m_i, q_i) in 2D or 3D, stored contiguously (one column per point).
#include <Eigen/Geometry>
#include <cstdint>
#include <optional>
#include <vector>

namespace verifybench {

/// Rigid motion in SE(Dim). Named by frames: T_target_source maps source points into the target
/// frame.
template <int Dim>
using Rigid = Eigen::Transform<double, Dim, Eigen::Isometry>;

template <int Dim>
struct Correspondences {
  using Points = Eigen::Matrix<double, Dim, Eigen::Dynamic>;
  Points source;  ///< m_i, one column per correspondence (source frame)
  Points target;  ///< q_i, one column per correspondence (target frame)

  Eigen::Index size() const { return source.cols(); }
  bool empty() const { return source.cols() == 0; }
};

/// What is known about a set beyond the points; never passed to a solver.
template <int Dim>
struct GroundTruth {
  std::optional<Rigid<Dim>> T_target_source;  ///< true motion, when known
  std::vector<std::uint8_t> labels;           ///< 1 = true inlier; empty when unknown
};

template <int Dim>
struct LabeledSet {
  Correspondences<Dim> corr;
  GroundTruth<Dim> truth;
};

/// Throws std::invalid_argument naming the first bad field: mismatched sizes or a non-finite
/// coordinate.
template <int Dim>
void validate(const Correspondences<Dim>& corr);

/// Throws std::invalid_argument when labels are present but their count differs from the set's.
template <int Dim>
void validate(const LabeledSet<Dim>& set);

}  // namespace verifybench
