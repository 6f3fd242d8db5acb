#pragma once
// Closed-form least-squares rigid fit (Arun et al. 1987; Umeyama 1991, without scale).
#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
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

/// The closed-form step shared by every fit: H = sum w (m - m_bar)(q - q_bar)^T = U S V^T gives
/// R = V D U^T with D = diag(1, ..., 1, det(V U^T)), and t = q_bar - R m_bar. `spread` is
/// sum w ||m - m_bar||^2, the scale of the rank test. nullopt when rank(H) < Dim - 1.
template <int Dim>
std::optional<Rigid<Dim>> rigid_from_moments(const Eigen::Matrix<double, Dim, Dim>& H,
                                             double spread,
                                             const Eigen::Matrix<double, Dim, 1>& mean_s,
                                             const Eigen::Matrix<double, Dim, 1>& mean_t) {
  using Mat = Eigen::Matrix<double, Dim, Dim>;
  Eigen::JacobiSVD<Mat> svd(H, Eigen::ComputeFullU | Eigen::ComputeFullV);
  // Rank test relative to the data's own scale: the rotation is unique when rank(H) >= Dim - 1.
  const double tol = 1e-12 * std::max(spread, 1e-300);
  if (!(spread > 0.0) || svd.singularValues()(Dim - 2) <= tol) return std::nullopt;
  Mat D = Mat::Identity();
  D(Dim - 1, Dim - 1) =
      (svd.matrixV() * svd.matrixU().transpose()).determinant() < 0.0 ? -1.0 : 1.0;
  Rigid<Dim> T = Rigid<Dim>::Identity();
  T.linear() = svd.matrixV() * D * svd.matrixU().transpose();
  T.translation() = mean_t - T.linear() * mean_s;
  return T;
}

/// Unweighted fit of K fixed-size pairs (minimal and small samples: no allocation).
template <int Dim, int K>
std::optional<Rigid<Dim>> fit_rigid_fixed(const Eigen::Matrix<double, Dim, K>& m,
                                          const Eigen::Matrix<double, Dim, K>& q) {
  const Eigen::Matrix<double, Dim, 1> mean_s = m.rowwise().mean(), mean_t = q.rowwise().mean();
  const Eigen::Matrix<double, Dim, K> ds = m.colwise() - mean_s;
  const Eigen::Matrix<double, Dim, Dim> H = ds * (q.colwise() - mean_t).transpose();
  return rigid_from_moments<Dim>(H, ds.squaredNorm(), mean_s, mean_t);
}

/// The same least-squares fit for minimal samples (2 pairs in 2D, 3 in 3D), several times faster
/// than the SVD: in 2D the angle is atan2(sum ds x dq, sum ds . dq); in 3D the right singular
/// vectors come from the closed-form eigen-decomposition of H^T H, u_i = H v_i / s_i for the two
/// largest, u_3 = u_1 x u_2, and R = v_1 u_1^T + v_2 u_2^T + det(V) v_3 u_3^T (Umeyama's D).
/// nullopt when the sample is degenerate (rank(H) < Dim - 1).
template <int Dim>
std::optional<Rigid<Dim>> fit_rigid_minimal(const Eigen::Matrix<double, Dim, Dim>& m,
                                            const Eigen::Matrix<double, Dim, Dim>& q) {
  using Vec = Eigen::Matrix<double, Dim, 1>;
  const Vec mean_s = m.rowwise().mean(), mean_t = q.rowwise().mean();
  const Eigen::Matrix<double, Dim, Dim> ds = m.colwise() - mean_s, dq = q.colwise() - mean_t;
  const double spread = ds.squaredNorm();
  Rigid<Dim> T = Rigid<Dim>::Identity();
  if constexpr (Dim == 2) {
    double c = 0.0, s = 0.0;
    for (int k = 0; k < 2; ++k) {
      c += ds.col(k).dot(dq.col(k));
      s += ds(0, k) * dq(1, k) - ds(1, k) * dq(0, k);
    }
    if (!(spread > 0.0) || std::hypot(c, s) <= 1e-12 * spread) return std::nullopt;
    const double angle = std::atan2(s, c);
    T.linear() << std::cos(angle), -std::sin(angle), std::sin(angle), std::cos(angle);
  } else {
    const Eigen::Matrix3d H = ds * dq.transpose();
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig;
    eig.computeDirect(H.transpose() * H);  // ascending eigenvalues s_i^2
    const Eigen::Matrix3d& V = eig.eigenvectors();
    const double s1 = std::sqrt(std::max(eig.eigenvalues()(2), 0.0));
    const double s2 = std::sqrt(std::max(eig.eigenvalues()(1), 0.0));
    if (!(spread > 0.0) || s2 <= 1e-6 * spread) return std::nullopt;
    const Eigen::Vector3d u1 = (H * V.col(2) / s1).normalized();
    Eigen::Vector3d u2 = H * V.col(1) / s2;
    u2 = (u2 - u2.dot(u1) * u1).normalized();
    const Eigen::Vector3d u3 = u1.cross(u2);
    // det of V ordered like U (largest first): [v_1 v_2 v_3] = V with columns reversed.
    const double d = V.col(2).cross(V.col(1)).dot(V.col(0)) < 0.0 ? -1.0 : 1.0;
    const Eigen::Matrix3d R0 =
        V.col(2) * u1.transpose() + V.col(1) * u2.transpose() + d * V.col(0) * u3.transpose();
    // The closed-form eigenvalues lose digits on thin triangles (up to ~1e-4): one Newton step on
    // max tr(R^T H^T) over R = R0 exp(w^) squares the error. With M = R0^T H^T, the gradient is
    // the skew part of M and the Hessian tr(M) I - sym(M).
    const Eigen::Matrix3d M = R0.transpose() * H.transpose();
    const Eigen::Vector3d g(M(2, 1) - M(1, 2), M(0, 2) - M(2, 0), M(1, 0) - M(0, 1));
    const Eigen::Matrix3d hess =
        M.trace() * Eigen::Matrix3d::Identity() - 0.5 * (M + M.transpose());
    const Eigen::Vector3d w = hess.ldlt().solve(g);
    const double angle = w.norm();
    T.linear() = angle > 0.0 && std::isfinite(angle)
                     ? Eigen::Matrix3d(R0 * Eigen::AngleAxisd(angle, w / angle).toRotationMatrix())
                     : R0;
  }
  T.translation() = mean_t - T.linear() * mean_s;
  return T;
}

/// All correspondences, unweighted.
template <int Dim>
std::optional<Rigid<Dim>> fit_rigid(const Correspondences<Dim>& corr);

/// Whether the selected correspondences pin down one rigid motion: at least 2 (2D) / 3 (3D) of
/// them, and on each side points that are not all coincident (2D) or not all collinear (3D: the
/// second largest eigenvalue of their covariance above 1e-10 of the largest). A selection that does
/// not is never accepted (solver.hpp decide()).
template <int Dim>
bool pins_motion(const Correspondences<Dim>& corr, const std::vector<int>& selected);

}  // namespace verifybench
