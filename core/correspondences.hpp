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

/// Degrees of freedom of SE(Dim): 3 in 2D, 6 in 3D.
template <int Dim>
constexpr int kPoseDof = Dim == 2 ? 3 : 6;

/// A guess of the motion and its uncertainty, as odometry gives it for a loop-closure candidate.
/// The covariance is that of the left perturbation delta = (rotation, translation) in
/// T = Exp(delta) * T_target_source: (theta, x, y) in 2D, (wx, wy, wz, x, y, z) in 3D.
template <int Dim>
struct PosePrior {
  Rigid<Dim> T_target_source = Rigid<Dim>::Identity();
  Eigen::Matrix<double, kPoseDof<Dim>, kPoseDof<Dim>> covariance =
      Eigen::Matrix<double, kPoseDof<Dim>, kPoseDof<Dim>>::Identity();
};

/// What a front end hands a verifier: the matched points and, optionally, a per-match score and a
/// pose prior. Never ground truth.
template <int Dim>
struct Correspondences {
  using Points = Eigen::Matrix<double, Dim, Eigen::Dynamic>;
  Points source;  ///< m_i, one column per correspondence (source frame)
  Points target;  ///< q_i, one column per correspondence (target frame)
  /// Empty, or one score per correspondence, higher = more likely correct (e.g. the negated
  /// descriptor distance); PROSAC samples in this order.
  std::vector<double> score;
  std::optional<PosePrior<Dim>> prior;  ///< odometry guess, when the caller has one (JCBB uses it)

  Eigen::Index size() const { return source.cols(); }
  bool empty() const { return source.cols() == 0; }
};

/// What is known about a set beyond the points; never passed to a solver.
template <int Dim>
struct GroundTruth {
  std::optional<Rigid<Dim>> T_target_source;  ///< true motion, when known
  std::vector<std::uint8_t> labels;           ///< 1 = true inlier; empty when unknown
  /// |R^T R - I|_F of the motion as its file published it, before projection onto SO(Dim)
  /// (core/transform.hpp); 0 when it was exact or drawn.
  double rotation_residual = 0.0;
  /// The expected decision: true for a real loop (a verifier should accept), false for a pair
  /// whose sides share no motion (it should reject); unset when unknown.
  std::optional<bool> positive;
};

template <int Dim>
struct LabeledSet {
  Correspondences<Dim> corr;
  GroundTruth<Dim> truth;
};

/// Throws std::invalid_argument naming the first bad field: mismatched sizes, a non-finite
/// coordinate or score, a score count that is not 0 or n, a prior covariance that is not finite,
/// symmetric and positive definite.
template <int Dim>
void validate(const Correspondences<Dim>& corr);

/// Throws std::invalid_argument when labels are present but their count differs from the set's.
template <int Dim>
void validate(const LabeledSet<Dim>& set);

}  // namespace verifybench
