#pragma once
// The exact parts of `quatro` and `robin-gnc` that the tests check against brute force:
//  - Quatro's quasi-SO(3) rotation (Lim, Lee, Myung, "A Single Correspondence Is Enough: Robust
//    Global Registration to Avoid Degeneracy in Urban Environments", ICRA 2022): with roll and
//    pitch taken as ~0 (a ground vehicle), R = R_z(theta), and the z row of every TIM
//    residual b - R a no longer depends on theta; the rotation is a planar one on the xy
//    components, estimated by GNC-TLS (Yang et al., RA-L 2020) whose weighted least-squares step
//    has the closed form weighted_yaw below (the SO(2) case of the Procrustes / Umeyama step);
//  - the selection stage of ROBIN (Shi, Yang, Carlone, ICRA 2021) as KISS-Matcher (Lim et al.,
//    ICRA 2025) runs it: the max k-core of the compatibility graph (default) or its max clique;
//  - the component-wise translation estimate (COTE) of TEASER (Yang, Shi, Carlone, T-RO 2020,
//    adaptive voting per axis) that both pipelines end with.
#include <Eigen/Core>
#include <cmath>
#include <optional>
#include <vector>

#include "cliques/max_clique.hpp"
#include "core/correspondences.hpp"
#include "solvers/detail/gnc.hpp"
#include "solvers/detail/teaser.hpp"

namespace verifybench {

/// argmin_theta sum_i w_i ||b_i - R(theta) a_i||^2 over 2-vectors: expanding the square,
///   sum_i w_i (|a_i|^2 + |b_i|^2) - 2 (cos(theta) C + sin(theta) S),
///   C = sum_i w_i a_i . b_i,  S = sum_i w_i (a_i x b_i)  (the z of the planar cross product),
/// least at theta = atan2(S, C). nullopt when (C, S) vanishes against the data's scale (no weight
/// on a non-zero TIM): the yaw is then undetermined.
inline std::optional<double> weighted_yaw(const Eigen::Matrix2Xd& a, const Eigen::Matrix2Xd& b,
                                          const std::vector<double>& w) {
  double C = 0.0, S = 0.0, scale = 0.0;
  for (Eigen::Index i = 0; i < a.cols(); ++i) {
    const double wi = w[static_cast<std::size_t>(i)];
    C += wi * (a(0, i) * b(0, i) + a(1, i) * b(1, i));
    S += wi * (a(0, i) * b(1, i) - a(1, i) * b(0, i));
    scale += wi * a.col(i).norm() * b.col(i).norm();
  }
  if (!(scale > 0.0) || std::hypot(C, S) <= 1e-12 * scale) return std::nullopt;
  return std::atan2(S, C);
}

struct YawGncOutcome {
  double yaw = 0.0;  ///< the estimate whose residuals gave gnc.weights [rad]
  GncOutcome gnc;
};

/// Quatro's quasi-SO(3) step: GNC-TLS (detail/gnc.hpp) over the planar TIM residuals
/// r_i = ||b_i - R(theta) a_i||, each weighted fit by weighted_yaw. `s.noise_bound` is the TIMs'
/// bound (2 beta: a TIM carries two points' noise).
inline YawGncOutcome gnc_tls_yaw(const Eigen::Matrix2Xd& a, const Eigen::Matrix2Xd& b,
                                 const GncSettings& s) {
  YawGncOutcome out;
  const auto fit = [&](const std::vector<double>& w) {
    const auto yaw = weighted_yaw(a, b, w);
    if (yaw) out.yaw = *yaw;
    return yaw.has_value();
  };
  const auto residuals_sq = [&](std::vector<double>& r2) {
    const Eigen::Matrix2d R = Eigen::Rotation2Dd(out.yaw).toRotationMatrix();
    for (Eigen::Index i = 0; i < a.cols(); ++i) {
      r2[static_cast<std::size_t>(i)] = (b.col(i) - R * a.col(i)).squaredNorm();
    }
  };
  out.gnc = gnc_tls(static_cast<int>(a.cols()), s, fit, residuals_sq);
  return out;
}

/// KISS-Matcher's robin_mode: the max k-core (its default, "max_core") or the max clique
/// ("max_clique"; the paper found it slower and no better).
struct RobinSelection {
  std::vector<int> vertices;  ///< ascending
  bool stopped = false;       ///< a time limit cut the clique search short
};

/// ROBIN's MAX_CORE structure: the vertices whose core number is the largest (Batagelj-Zaversnik
/// peeling). Empty when that number is 0 (no edge: no two correspondences agree, nothing to keep).
/// MAX_CLIQUE: the exact maximum clique (best so far past the time limit).
inline RobinSelection robin_select(const BitGraph& g, bool max_clique, double time_left_s,
                                   int threads, std::uint64_t seed) {
  RobinSelection out;
  if (!max_clique) {
    if (auto core = max_kcore_selection(g, 0.0)) out.vertices = std::move(*core);
    return out;
  }
  register_clique_algorithms();
  CliqueSearchParams search;
  search.time_limit_s = time_left_s;
  search.threads = threads;
  search.seed = seed;
  const CliqueSearchResult clique = CliqueAlgorithms::get(kDefaultCliqueAlgorithm).run(g, search);
  out.vertices = clique.clique;
  out.stopped = clique.stopped;
  return out;
}

template <int Dim>
struct CoteOutcome {
  Eigen::Matrix<double, Dim, 1> t = Eigen::Matrix<double, Dim, 1>::Zero();
  std::vector<int> inliers;  ///< the members within beta of t on every axis, in members' order
};

/// COTE: each axis d of t_i = q_i - R m_i over `members` by adaptive voting (TEASER's scalar TLS,
/// intervals [t_i - beta, t_i + beta]); a member is an inlier when it is within beta on every axis
/// (TEASER++'s and Quatro's TLSTranslationSolver). `members` non-empty.
template <int Dim>
CoteOutcome<Dim> component_translation(const Correspondences<Dim>& corr,
                                       const Eigen::Matrix<double, Dim, Dim>& R,
                                       const std::vector<int>& members, double beta) {
  CoteOutcome<Dim> out;
  std::vector<char> inside(members.size(), 1);
  std::vector<double> t(members.size());
  for (int d = 0; d < Dim; ++d) {
    for (std::size_t v = 0; v < members.size(); ++v) {
      t[v] = (corr.target.col(members[v]) - R * corr.source.col(members[v]))(d);
    }
    const double td = adaptive_vote(t, beta).estimate;
    out.t(d) = td;
    for (std::size_t v = 0; v < members.size(); ++v) inside[v] &= std::abs(t[v] - td) <= beta;
  }
  for (std::size_t v = 0; v < members.size(); ++v) {
    if (inside[v]) out.inliers.push_back(members[v]);
  }
  return out;
}

/// The chain of TIMs over a selection of k >= 2 (TEASER++'s default CHAIN graph, which Quatro
/// and KISS-Matcher keep): TIM p joins selection[p] to selection[(p + 1) % k].
template <int Dim>
void chain_tims(const Correspondences<Dim>& corr, const std::vector<int>& selected,
                Eigen::Matrix<double, Dim, Eigen::Dynamic>& a,
                Eigen::Matrix<double, Dim, Eigen::Dynamic>& b) {
  const std::size_t k = selected.size();
  a.resize(Dim, static_cast<Eigen::Index>(k));
  b.resize(Dim, static_cast<Eigen::Index>(k));
  for (std::size_t p = 0; p < k; ++p) {
    const int i = selected[p], j = selected[(p + 1) % k];
    a.col(static_cast<Eigen::Index>(p)) = corr.source.col(j) - corr.source.col(i);
    b.col(static_cast<Eigen::Index>(p)) = corr.target.col(j) - corr.target.col(i);
  }
}

}  // namespace verifybench
