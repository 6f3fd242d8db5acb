#include "acceptance/runner_up.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>

#include "acceptance/prior_gate.hpp"
#include "core/random.hpp"
#include "core/timer.hpp"
#include "graph/bitgraph.hpp"
#include "solvers/registry.hpp"

namespace verifybench {

double explained_tolerance(const SolverParams& params) {
  return std::max(params.eps, params.inlier_threshold);
}

bool comparable(int runner, int best, const NullFit& null) {
  return runner - null.location >= kComparable * (best - null.location);
}

namespace {

/// Median distance between where `a` and `b` put the source points of `inliers`, over `tol`.
template <int Dim>
double median_separation(const Correspondences<Dim>& corr, const std::vector<int>& inliers,
                         const Rigid<Dim>& a, const Rigid<Dim>& b, double tol) {
  if (inliers.empty()) return 0.0;
  std::vector<double> moved;
  moved.reserve(inliers.size());
  for (int i : inliers) {
    const auto m = corr.source.col(i);
    moved.push_back((a * m - b * m).norm());
  }
  auto mid = moved.begin() + static_cast<std::ptrdiff_t>(moved.size() / 2);
  std::nth_element(moved.begin(), mid, moved.end());
  return *mid / tol;
}

/// Drops from `rest` (indices into corr) the correspondences `T` explains within kExplained
/// tolerances, and `taken` ones (indices into the subset `rest` was solved as).
template <int Dim>
void drop_explained(const Correspondences<Dim>& corr, const Rigid<Dim>& T, double tol,
                    const std::vector<int>& taken, std::vector<Eigen::Index>& rest) {
  std::vector<char> out(rest.size(), 0);
  for (int k : taken) out[static_cast<std::size_t>(k)] = 1;
  std::vector<Eigen::Index> kept;
  kept.reserve(rest.size());
  for (std::size_t k = 0; k < rest.size(); ++k) {
    const Eigen::Index i = rest[k];
    if (out[k] || (T * corr.source.col(i) - corr.target.col(i)).norm() <= kExplained * tol) continue;
    kept.push_back(i);
  }
  rest.swap(kept);
}

template <int Dim>
Correspondences<Dim> subset(const Correspondences<Dim>& corr, const std::vector<Eigen::Index>& rest) {
  Correspondences<Dim> sub;
  sub.source.resize(Dim, static_cast<Eigen::Index>(rest.size()));
  sub.target.resize(Dim, static_cast<Eigen::Index>(rest.size()));
  for (std::size_t k = 0; k < rest.size(); ++k) {
    sub.source.col(static_cast<Eigen::Index>(k)) = corr.source.col(rest[k]);
    sub.target.col(static_cast<Eigen::Index>(k)) = corr.target.col(rest[k]);
    if (!corr.score.empty()) sub.score.push_back(corr.score[static_cast<std::size_t>(rest[k])]);
  }
  sub.prior = corr.prior;
  return sub;
}

}  // namespace

template <int Dim>
std::optional<RunnerUp> runner_up(const Solver& solver, const Correspondences<Dim>& corr,
                                  const Result<Dim>& accepted, const SolverParams& params,
                                  const Calibration& calibration, const AcceptParams& accept,
                                  const Deadline& budget, NullDraws* draws) {
  const StopWatch clock;
  // The search the runner-ups are found and calibrated with: the solver's own, or `clique` for a
  // solver without one (GNC from one start converges to a blend of equal copies, or to nothing,
  // and so never finds a periodic scene's family: BENCHMARK.md 40).
  std::unique_ptr<Solver> clique;
  if (!solver.searches() && BitGraph::bytes_for(corr.size()) <= params.max_graph_bytes) {
    register_solvers();
    clique = SolverRegistry::create("clique");
  }
  const Solver& search = clique ? *clique : solver;
  // The search's null draws, each solved once over the rivals' calibrations (the solver's come
  // from the accepted motion's).
  NullDraws clique_draws;
  NullDraws* search_draws = clique ? &clique_draws : draws;
  const double tol = explained_tolerance(params);
  const Rigid<Dim>& T = accepted.T_target_source;
  const int best = static_cast<int>(accepted.inliers.size());
  // The rest: what the accepted motion does not explain (its inliers and their near copies).
  std::vector<Eigen::Index> rest(static_cast<std::size_t>(corr.size()));
  for (Eigen::Index i = 0; i < corr.size(); ++i) rest[static_cast<std::size_t>(i)] = i;
  {
    std::vector<int> own(accepted.inliers.begin(), accepted.inliers.end());
    drop_explained(corr, T, tol, own, rest);
  }
  std::optional<RunnerUp> out;
  // The rivals found so far: their motions and inliers (indices into corr).
  std::vector<Rigid<Dim>> rival_motions;
  std::vector<std::vector<int>> rival_inliers;
  for (int round = 0; round < kMaxRivals && rest.size() >= 2; ++round) {
    const Correspondences<Dim> sub = subset(corr, rest);
    SolverParams p = params;
    p.time_limit_s = std::min(params.time_limit_s, budget.limit_s());
    p.seed = round == 0 ? derive_seed(params.seed, {kRunnerUpStream})
                        : derive_seed(params.seed, {kRunnerUpStream, static_cast<std::uint64_t>(round)});
    const Result<Dim> r = search.solve(sub, p);
    if (r.status == Status::error) break;
    const int score = static_cast<int>(r.inliers.size());
    std::vector<int> found;  // r's inliers as indices into corr
    found.reserve(r.inliers.size());
    for (int k : r.inliers) found.push_back(static_cast<int>(rest[static_cast<std::size_t>(k)]));
    const double separation = median_separation(corr, accepted.inliers, T, r.T_target_source, tol);
    // The accepted motion again (its remnant split by noise or a k-NN matching's neighbouring
    // targets), or an earlier rival again (its near copy): not a motion of its own, so it is not
    // counted; its correspondences go and the search goes on behind it.
    bool repeat = separation <= kSameMotion || !pins_motion(sub, r.inliers);
    for (std::size_t j = 0; j < rival_motions.size() && !repeat; ++j) {
      repeat = median_separation(corr, rival_inliers[j], rival_motions[j], r.T_target_source, tol) <=
               kSameMotion;
    }
    const bool limited_solve = r.status == Status::time_limit;
    auto note = [&](double p_value, bool limited) {  // the first runner-up's figures, whatever it is
      if (!out) {
        out.emplace();
        out->score = score;
        out->p_value = p_value;
        out->separation = separation;
      }
      out->time_limit = out->time_limit || limited;
    };
    // Below 0.4 of the accepted motion's score no null makes it comparable (comparable() needs
    // score >= 0.4 best + 0.6 mu, mu >= 0), nor anything the solver finds after it: no calibration.
    if (10LL * score < 4LL * best) {
      note(std::numeric_limits<double>::quiet_NaN(), limited_solve);
      break;
    }
    if (repeat && out) {
      note(out->p_value, limited_solve);
      drop_explained(corr, r.T_target_source, tol, r.inliers, rest);
      continue;
    }
    // Its p: the calibrated rule's own, as if this motion were the pair's score, at
    // runner_up_alpha (calibrate(): the same permuted sets, the screen's bounds first, then solved
    // draws that stop early, more draws where the range of p holds the level). So it is
    // significant exactly when the rule would accept that score.
    AcceptParams at = accept;
    at.alpha = accept.runner_up_level();
    const Calibration own = calibrate(search, corr, params, at, score, budget, search_draws);
    // The chance level the excesses are measured from: solved draws where either null has them
    // (the search's own where it is not the solver's, screened or not).
    const NullFit& null =
        !own.screened || calibration.screened || clique ? own.null : calibration.null;
    note(own.p_value, limited_solve || own.budget_exhausted);
    if (repeat) {
      drop_explained(corr, r.T_target_source, tol, r.inliers, rest);
      continue;
    }
    // The solver takes the largest motion left first, so once one is not significant or not
    // comparable, none after it is.
    if (!(own.p_value < accept.runner_up_level()) || !comparable(score, best, null)) break;
    bool competes = true;
    if (accept.prior_gate > 0.0) {
      if (const auto d2 = prior_distance2(corr, r.T_target_source)) {
        competes = inside_prior_gate<Dim>(*d2, accept.prior_gate);
      }
    }
    if (competes) {
      ++out->rivals;
      out->rival_support += score;
      // The decision: the accepted motion must outweigh its comparable rivals together.
      if (out->rival_support >= best) {
        out->ambiguous = true;
        break;
      }
      rival_motions.push_back(r.T_target_source);
      rival_inliers.push_back(std::move(found));
    }
    drop_explained(corr, r.T_target_source, tol, r.inliers, rest);
  }
  if (out) out->ms = clock.ms();
  return out;
}

template std::optional<RunnerUp> runner_up<2>(const Solver&, const Correspondences<2>&,
                                              const Result<2>&, const SolverParams&,
                                              const Calibration&, const AcceptParams&,
                                              const Deadline&, NullDraws*);
template std::optional<RunnerUp> runner_up<3>(const Solver&, const Correspondences<3>&,
                                              const Result<3>&, const SolverParams&,
                                              const Calibration&, const AcceptParams&,
                                              const Deadline&, NullDraws*);

}  // namespace verifybench
