#pragma once
// The calibrated accept rule (issue #13): the same solver, run on K sets whose targets are
// re-paired at random, gives the chance distribution of its score for this pair (both clouds'
// geometry, n, eps and the matching's many-to-one structure kept); the pair is accepted when its
// own score has p < alpha under the Gumbel law fitted to those K scores (null_model.hpp).
#include <cstdint>
#include <vector>

#include "acceptance/accept_params.hpp"
#include "acceptance/null_model.hpp"
#include "core/correspondences.hpp"
#include "core/deadline.hpp"
#include "solvers/solver.hpp"

namespace verifybench {

/// The permutation null's set: each distinct target point is replaced by another distinct target
/// point of the set (one seeded permutation), so correspondences that shared a target still share
/// one, and sources, scores and the prior stay as they were.
template <int Dim>
Correspondences<Dim> permute_targets(const Correspondences<Dim>& corr, std::uint64_t seed);

/// Which correspondences share a target point: the part of permute_targets that is the same for
/// every seed (a hash table), computed once per calibration.
struct TargetGroups {
  std::vector<int> group;  ///< per correspondence: its target's group, numbered by first appearance
  std::vector<int> first;  ///< per group: its first correspondence
};

template <int Dim>
TargetGroups target_groups(const Correspondences<Dim>& corr);

/// permute_targets with the groups of `corr` computed beforehand (the same set for the same
/// seed). Throws std::invalid_argument when the groups are not of a set of this size.
template <int Dim>
Correspondences<Dim> permute_targets(const Correspondences<Dim>& corr, const TargetGroups& groups,
                                     std::uint64_t seed);

struct Calibration {
  NullFit null;
  double p_value = 1.0;
  /// The p that these draws cannot tell apart from p_value: optimistic_fit's and cautious_fit's
  /// (null_model.hpp). A decision whose range holds alpha may go either way under other draws.
  double p_value_low = 1.0, p_value_high = 1.0;
  int threshold = 0;        ///< the smallest score accepted at alpha
  int limited_draws = 0;    ///< null solves stopped by the time limit (their upper bound counted)
  /// Accepted by the screen: `null` was fitted to the solver's score bounds on the first
  /// null.draws permuted sets, and no null set was solved.
  bool screened = false;
  int screen_part_size = 0;  ///< when screened: the bounds' part size (kScreenPartSizes)
  double ms = 0.0;          ///< wall time of the null solves
  /// The pair's budget ran out before the draws settled the decision: the draws made decide by
  /// their cautious fit (p_value = p_value_high) when there are kMinDrawsToAccept of them, else
  /// p = 1; either way a decision more time could change (a report's `provisional`).
  bool budget_exhausted = false;
};

/// The null draws one calibration solved, by draw index: what calibrations of other scores on the
/// same set, with the same solver and parameters, would solve again (the runner-up test's rivals,
/// runner_up.hpp). A draw's set and seed come from params.seed and its index alone, so a draw
/// kept here is taken as it is instead of solved again: the same result wherever the pair's budget
/// does not run out. Where it does, kept draws are still taken after it (a calibration goes as far
/// as the draws already solved, for any thread count), and a draw a shorter remaining budget
/// stopped at its limit (an upper bound counted) may be taken solved. Draws the budget cut short
/// without a bound are not kept.
struct NullDraws {
  std::vector<int> score;      ///< per draw index: its score (an upper bound where limited); -1 = not solved
  std::vector<char> limited;   ///< stopped by the time limit
};

/// Runs `solver` on up to accept.null_draws = K permuted sets (draw k from
/// derive_seed(params.seed, {kNullStream, k}); the solver's own seed derived the same way) and
/// scores `observed` against them. Stops early where the decision of all K draws is already known:
/// at the first draw that reaches `observed` (p >= 2 / (K + 1) >= alpha from then on; a single
/// such draw leaves p = 1), or after kMinDrawsToAccept draws when even cautious_fit() puts
/// `observed` below alpha. After K draws, where the range of p [optimistic_fit, cautious_fit]
/// still holds alpha, draws on until it does not or accept.max_null_draws ran; the plain
/// fit of all the draws then decides. null.draws says how many ran. A null solve stopped by the
/// time limit counts with its proven
/// upper bound when it has one (clique solvers), so a limit never makes chance look smaller.
/// First, when the solver has a score bound (Solver::score_bound), a screen: the bounds of the
/// permuted sets (the same sets the draws would solve, at least kMinDrawsToAccept, at most K) are
/// a null of a statistic that is never below the score, so when even cautious_fit() of the bounds
/// puts `observed` below alpha the pair is accepted without a null solve (the early accept's test,
/// on a stochastically larger null); coarse bounds first, finer ones where they do not settle it
/// (kScreenPartSizes); otherwise the draws run as above, resolve_threads(params.threads) at a
/// time on one thread each when the solver solves_concurrently() (the same result for any count).
/// The draws share `budget` (the pair's deadline, verify()): each null solve may take what is
/// left, and none starts once it passed (budget_exhausted).
/// `draws`, when given, supplies the draws an earlier calibration of this set solved and keeps
/// those this one solves (NullDraws); the result is the same with or without it where the budget
/// does not run out.
/// Throws std::runtime_error when a null solve fails.
template <int Dim>
Calibration calibrate(const Solver& solver, const Correspondences<Dim>& corr,
                      const SolverParams& params, const AcceptParams& accept, int observed,
                      const Deadline& budget = Deadline::never(), NullDraws* draws = nullptr);

/// Applies the rule to a finished solve: under `count` leaves the solver's decision; under
/// `pvalue` accepts when p < alpha, the inliers pin down a motion (pins_motion) and, where the set
/// carries a pose prior and accept.prior_gate > 0, the fitted motion is inside the prior's
/// gate (prior_gate.hpp); and sets status ok / rejected to match (time_limit and error stay).
template <int Dim>
void decide_calibrated(Result<Dim>& result, const Correspondences<Dim>& corr,
                       const Calibration& calibration, const AcceptParams& accept);

/// The screen's levels: score bounds by parts of these many correspondences, coarse (cheap,
/// loose) first. Parts of up to 64 are solved exactly on one word per row (clique_number_bound):
/// parts of 8 cost about n * 4 pair tests and bound near n / 4, parts of 64 about n * 32 and near
/// n / 15 on the corpus' nulls; parts of 2,048 a tenth of the whole graph at n = 12,000 (BENCHMARK.md
/// sections 22 and 24). A clear positive passes at the first level that is below it.
inline constexpr int kScreenPartSizes[] = {8, 16, 64, 2048};

/// Draws before an early accept.
inline constexpr int kMinDrawsToAccept = 3;

inline constexpr std::uint64_t kNullStream = 0x6e756c6cull;  // "null"

}  // namespace verifybench
