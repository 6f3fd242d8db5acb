#include "loop/pose_graph.hpp"

#include <ceres/ceres.h>

#include <cmath>
#include <stdexcept>
#include <string>

namespace verifybench {
namespace {

// The relative-pose residual of the header, templated for Ceres' automatic differentiation.
// Parameters: translation (3) and quaternion (x, y, z, w: Eigen's storage order) of a and b.
struct RelativePoseError {
  Eigen::Quaterniond q_ab;
  Eigen::Vector3d t_ab;
  Eigen::Matrix<double, 6, 1> inv_sigma;

  template <class T>
  bool operator()(const T* ta, const T* qa, const T* tb, const T* qb, T* residual) const {
    const Eigen::Map<const Eigen::Matrix<T, 3, 1>> pa(ta), pb(tb);
    const Eigen::Map<const Eigen::Quaternion<T>> Qa(qa), Qb(qb);
    const Eigen::Quaternion<T> Qa_inv = Qa.conjugate();
    const Eigen::Quaternion<T> q_ab_est = Qa_inv * Qb;
    const Eigen::Matrix<T, 3, 1> t_ab_est = Qa_inv * (pb - pa);
    const Eigen::Quaternion<T> q_inv = q_ab.template cast<T>().conjugate();
    const Eigen::Quaternion<T> dq = q_inv * q_ab_est;
    const Eigen::Matrix<T, 3, 1> dt = q_inv * (t_ab_est - t_ab.template cast<T>());
    // Sign of the quaternion: the shorter rotation.
    const T s = dq.w() < T(0) ? T(-2) : T(2);
    residual[0] = s * dq.x() * T(inv_sigma(0));
    residual[1] = s * dq.y() * T(inv_sigma(1));
    residual[2] = s * dq.z() * T(inv_sigma(2));
    for (int k = 0; k < 3; ++k) residual[3 + k] = dt(k) * T(inv_sigma(3 + k));
    return true;
  }
};

}  // namespace

PoseGraphResult optimise_pose_graph(const std::vector<Rigid<3>>& initial,
                                    const std::vector<PoseEdge>& edges,
                                    const PoseGraphParams& params) {
  const int n = static_cast<int>(initial.size());
  PoseGraphResult result;
  result.poses = initial;
  if (n < 2 || edges.empty()) return result;
  std::vector<Eigen::Vector3d> t(n);
  std::vector<Eigen::Quaterniond> q(n);
  for (int i = 0; i < n; ++i) {
    t[i] = initial[i].translation();
    q[i] = Eigen::Quaterniond(initial[i].linear()).normalized();
  }
  ceres::Problem problem;
  for (std::size_t k = 0; k < edges.size(); ++k) {
    const PoseEdge& e = edges[k];
    if (e.from < 0 || e.from >= n || e.to < 0 || e.to >= n || e.from == e.to) {
      throw std::invalid_argument("pose graph: edge " + std::to_string(k) + " joins nodes " +
                                  std::to_string(e.from) + " and " + std::to_string(e.to) +
                                  " of " + std::to_string(n));
    }
    if (!(e.sigma.array() > 0.0).all() || !e.sigma.allFinite()) {
      throw std::invalid_argument("pose graph: edge " + std::to_string(k) +
                                  " has a sigma that is not positive and finite");
    }
    auto* cost = new ceres::AutoDiffCostFunction<RelativePoseError, 6, 3, 4, 3, 4>(
        new RelativePoseError{Eigen::Quaterniond(e.T_from_to.linear()).normalized(),
                              e.T_from_to.translation(), e.sigma.cwiseInverse()});
    ceres::LossFunction* loss = (params.robust && e.loop) ? new ceres::CauchyLoss(1.0) : nullptr;
    problem.AddResidualBlock(cost, loss, t[e.from].data(), q[e.from].coeffs().data(),
                             t[e.to].data(), q[e.to].coeffs().data());
  }
  for (int i = 0; i < n; ++i) {
    if (problem.HasParameterBlock(q[i].coeffs().data())) {
      problem.SetManifold(q[i].coeffs().data(), new ceres::EigenQuaternionManifold);
    }
  }
  if (problem.HasParameterBlock(t[0].data())) {
    problem.SetParameterBlockConstant(t[0].data());
    problem.SetParameterBlockConstant(q[0].coeffs().data());
  }
  ceres::Solver::Options options;
  options.max_num_iterations = params.max_iterations;
  // Local maps are few (tens to hundreds): dense normal equations unless sparse ones pay.
  options.linear_solver_type = n <= 300 ? ceres::DENSE_NORMAL_CHOLESKY : ceres::SPARSE_NORMAL_CHOLESKY;
  options.num_threads = 1;
  options.logging_type = ceres::SILENT;
  ceres::Solver::Summary summary;
  ceres::Solve(options, &problem, &summary);
  result.initial_cost = summary.initial_cost;
  result.final_cost = summary.final_cost;
  result.iterations = static_cast<int>(summary.iterations.size());
  result.converged = summary.termination_type == ceres::CONVERGENCE;
  for (int i = 0; i < n; ++i) {
    Rigid<3> T = Rigid<3>::Identity();
    T.linear() = q[i].normalized().toRotationMatrix();
    T.translation() = t[i];
    result.poses[i] = T;
  }
  return result;
}

}  // namespace verifybench
