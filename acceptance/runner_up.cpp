#include "acceptance/runner_up.hpp"

#include <algorithm>
#include <cmath>

#include "acceptance/prior_gate.hpp"
#include "core/random.hpp"

namespace verifybench {

double explained_tolerance(const SolverParams& params) {
  return std::max(params.eps, params.inlier_threshold);
}

bool comparable(int runner, int best, const NullFit& null) {
  return runner - null.location >= kComparable * (best - null.location);
}

template <int Dim>
std::optional<RunnerUp> runner_up(const Solver& solver, const Correspondences<Dim>& corr,
                                  const Result<Dim>& accepted, const SolverParams& params,
                                  const Calibration& calibration, const AcceptParams& accept,
                                  const Deadline& budget) {
  const double tol = explained_tolerance(params);
  const Rigid<Dim>& T = accepted.T_target_source;
  // The rest: what the accepted motion does not explain (its inliers and their near copies).
  std::vector<char> taken(static_cast<std::size_t>(corr.size()), 0);
  for (int i : accepted.inliers) taken[static_cast<std::size_t>(i)] = 1;
  std::vector<Eigen::Index> rest;
  for (Eigen::Index i = 0; i < corr.size(); ++i) {
    if (taken[static_cast<std::size_t>(i)]) continue;
    if ((T * corr.source.col(i) - corr.target.col(i)).norm() <= kExplained * tol) continue;
    rest.push_back(i);
  }
  if (rest.size() < 2) return std::nullopt;
  Correspondences<Dim> sub;
  sub.source.resize(Dim, static_cast<Eigen::Index>(rest.size()));
  sub.target.resize(Dim, static_cast<Eigen::Index>(rest.size()));
  for (std::size_t k = 0; k < rest.size(); ++k) {
    sub.source.col(static_cast<Eigen::Index>(k)) = corr.source.col(rest[k]);
    sub.target.col(static_cast<Eigen::Index>(k)) = corr.target.col(rest[k]);
    if (!corr.score.empty()) sub.score.push_back(corr.score[static_cast<std::size_t>(rest[k])]);
  }
  sub.prior = corr.prior;

  SolverParams p = params;
  p.time_limit_s = std::min(params.time_limit_s, budget.limit_s());
  p.seed = derive_seed(params.seed, {kRunnerUpStream});
  const Result<Dim> r = solver.solve(sub, p);
  RunnerUp out;
  if (r.status == Status::error) return std::nullopt;
  out.score = static_cast<int>(r.inliers.size());
  out.time_limit = r.status == Status::time_limit;
  // The runner-up's p: the calibrated rule's own, as if the runner-up were the pair's score, at
  // runner_up_alpha (calibrate(): the same permuted sets, the screen's bounds first, then solved
  // draws that stop early, a cautious fit before an early accept, more draws where the range of p
  // holds the level). So it is significant exactly when the rule would accept that score, whether
  // the pair's own null was of a few draws or of the screen's bounds (too loose for a smaller
  // score).
  AcceptParams at = accept;
  at.alpha = accept.runner_up_alpha;
  const Calibration own = calibrate(solver, corr, params, at, out.score, budget);
  out.p_value = own.p_value;
  out.time_limit = out.time_limit || own.budget_exhausted;
  // The chance level the excesses are measured from: solved draws where either null has them.
  const NullFit& null = !own.screened || calibration.screened ? own.null : calibration.null;
  std::vector<double> moved;
  moved.reserve(accepted.inliers.size());
  for (int i : accepted.inliers) {
    const auto m = corr.source.col(i);
    moved.push_back((T * m - r.T_target_source * m).norm());
  }
  if (!moved.empty()) {
    auto mid = moved.begin() + static_cast<std::ptrdiff_t>(moved.size() / 2);
    std::nth_element(moved.begin(), mid, moved.end());
    out.separation = *mid / tol;
  }
  bool competes = out.p_value < accept.runner_up_alpha &&
                  comparable(out.score, static_cast<int>(accepted.inliers.size()), null) &&
                  out.separation > kSameMotion && pins_motion(sub, r.inliers);
  if (competes && accept.prior_gate > 0.0) {
    if (const auto d2 = prior_distance2(corr, r.T_target_source)) {
      competes = inside_prior_gate<Dim>(*d2, accept.prior_gate);
    }
  }
  out.ambiguous = competes;
  return out;
}

template std::optional<RunnerUp> runner_up<2>(const Solver&, const Correspondences<2>&,
                                              const Result<2>&, const SolverParams&,
                                              const Calibration&, const AcceptParams&,
                                              const Deadline&);
template std::optional<RunnerUp> runner_up<3>(const Solver&, const Correspondences<3>&,
                                              const Result<3>&, const SolverParams&,
                                              const Calibration&, const AcceptParams&,
                                              const Deadline&);

}  // namespace verifybench
