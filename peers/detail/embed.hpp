#pragma once
// For the library peers (PCL, Open3D), which work in 3D only: 2D sets are embedded at z = 0 and
// the 3D answer is projected back.
#include <cmath>
#include <optional>
#include <string>

#include "core/correspondences.hpp"
#include "core/detail/killable_child.hpp"
#include "core/timer.hpp"
#include "solvers/detail/consensus.hpp"

namespace verifybench {

/// The i-th point of a side as a 3D point (z = 0 in 2D).
template <int Dim>
Eigen::Vector3d embed(const typename Correspondences<Dim>::Points& side, Eigen::Index i) {
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
  p.head<Dim>() = side.col(i);
  return p;
}

/// A 3D motion as a motion of SE(Dim); nullopt when a 2D set's answer tilts the plane by more
/// than a degree (with all points at z = 0, a half turn about an in-plane axis fits as well as a
/// rotation: it is a reflection of the 2D set, which 3D-only libraries may return).
template <int Dim>
std::optional<Rigid<Dim>> project(const Eigen::Matrix4d& M) {
  if (!M.allFinite()) return std::nullopt;
  Rigid<Dim> T = Rigid<Dim>::Identity();
  if constexpr (Dim == 3) {
    T.matrix() = M;
  } else {
    if (M(2, 2) < std::cos(M_PI / 180.0)) return std::nullopt;
    T.linear() = Eigen::Rotation2Dd(std::atan2(M(1, 0), M(0, 0))).toRotationMatrix();
    T.translation() = M.block<2, 1>(0, 3);
  }
  return T;
}

/// The answer of a library peer: its motion as is (no refit), the given correspondences it maps
/// within the inlier threshold, accepted or not. A motion that leaves a 2D set's plane is a
/// rejection with the identity, and the message says so.
template <int Dim>
void take_library_answer(const Eigen::Matrix4d& M, const Correspondences<Dim>& corr,
                         const SolverParams& params, const char* who, Result<Dim>& result) {
  const auto T = project<Dim>(M);
  if (!T) {
    result.T_target_source = Rigid<Dim>::Identity();
    result.inliers.clear();
    result.accepted = false;
    result.status = Status::rejected;
    result.message =
        std::string(who) + " returned a motion out of the 2D set's plane (a reflection)";
    return;
  }
  result.T_target_source = *T;
  result.inliers = consensus_set(corr, *T, params.inlier_threshold);
  decide(result, corr, params, true);
}

/// Runs `library()` (the library's 4x4 answer) in a forked child killed at --time-limit, so that a
/// peer honours the limit and what it sets process-wide (PCL's std::srand, OpenMP's thread count)
/// stays in the child; then takes its answer. Past the limit: the identity, nothing accepted,
/// status time_limit. The search time includes the fork (about a millisecond).
template <int Dim, class Library>
void run_library_peer(const Correspondences<Dim>& corr, const SolverParams& params, const char* who,
                      Library library, Result<Dim>& result) {
  StopWatch clock;
  const auto answer = detail::run_in_child(deadline_after(params.time_limit_s), [&] {
    const Eigen::Matrix4d M = library();
    return std::vector<double>(M.data(), M.data() + 16);
  });
  result.times.search_ms = clock.ms();
  if (!answer) {
    result.T_target_source = Rigid<Dim>::Identity();
    result.inliers.clear();
    result.accepted = false;
    result.status = Status::time_limit;
    result.message = std::string(who) + " was stopped at the time limit";
    return;
  }
  take_library_answer<Dim>(Eigen::Map<const Eigen::Matrix4d>(answer->data()), corr, params, who,
                           result);
}

}  // namespace verifybench
