#pragma once
// The runner-up test (issue #31): a rigid alias is a second motion the matching supports about as
// well as the first. Repetitive structure (a street's ground, a corridor, a row of pillars) gives
// a descriptor that cannot tell one copy from another, so a negative pair has several motions of
// similar consensus and a permutation null, which destroys that structure, finds each of them far
// beyond chance. A true motion leaves, once its own correspondences are taken away, only what
// chance gives, or a few weaker aliases (a symmetric room, a facade repeated once). So: remove
// every correspondence the accepted motion explains (residual ||T m_i - q_i|| within kExplained
// tolerances), solve the rest with the same solver (with `clique` where the solver has no search of
// its own: Solver::searches()), and count that runner-up as a rival when it is itself significant
// (p < runner_up_alpha under the pair's null, calibration.hpp), comparable to the accepted motion
// (comparable()), moves the accepted inliers elsewhere (a motion of its own, not the same one split
// by noise) and, where the set carries a pose prior, lies inside the prior's gate too (a prior that
// tells the two apart decides). While rivals are found, take their correspondences away too and
// solve again; a runner-up that is the accepted motion or an earlier rival again (within
// kSameMotion tolerances: a remnant split by noise, a k-NN matching's near copy) is taken away
// uncounted and the search goes on behind it. The pair is ambiguous when its rivals together hold
// at least as many inliers as the accepted motion: one alias as large as the truth (a tie), or a
// family of copies (a periodic scene's shifts by one, two, ... periods) that outweighs any one of
// them. A true motion with one weaker alias is kept, whatever the ratio of the two. Each rival's p
// is the calibrated rule's for its score (the same permuted sets).
// BENCHMARK.md sections 36, 38 and 40 measure it.
#include <optional>

#include "acceptance/accept_params.hpp"
#include "acceptance/calibration.hpp"
#include "core/correspondences.hpp"
#include "core/deadline.hpp"
#include "solvers/solver.hpp"

namespace verifybench {

struct RunnerUp {
  // The first runner-up (the largest motion the rest holds):
  int score = 0;          ///< its selection size
  /// of `score` under the pair's null: calibrate() of `score` at runner_up_alpha with the search
  /// that found it (the solver, or clique's for a solver without a search); NaN where it was not
  /// calibrated (a score under 0.4 of the accepted one's, which no null makes comparable)
  double p_value = 1.0;
  /// Median distance between where the accepted motion and the runner-up's put the accepted
  /// inliers' source points, over the tolerance: <= kSameMotion means one motion.
  double separation = 0.0;
  int rivals = 0;         ///< motions found that compete with the accepted one (see above)
  int rival_support = 0;  ///< their inliers together
  bool time_limit = false;  ///< a runner-up's solve was stopped (its score a lower bound)
  double ms = 0.0;          ///< wall time of the runner-up solves and their calibrations
  bool ambiguous = false;   ///< the decision: rival_support >= the accepted motion's inliers
};

/// The tolerance a correspondence counts as explained by a motion within: the larger of the
/// graph's eps and the consensus inlier threshold.
double explained_tolerance(const SolverParams& params);

/// The runner-up of `accepted` (a result the rule accepted, `calibration` its null) on `corr`;
/// nullopt when nothing is left to solve or the solve failed. The solves take what is left of
/// `budget`; the runner-up's seed is derived from params.seed. `draws`: the null draws the
/// accepted motion's calibration solved (calibrate()), taken again by the rivals' calibrations
/// (neither read nor extended where clique searches instead of the solver).
/// Where clique stands in for a solver without a search (Solver::searches()), the rivals' scores
/// are clique sizes (pairs within eps, Eq. (1)) compared with the solver's inlier count (residuals
/// within inlier_threshold), and their excesses are measured from the clique's null (its screen's
/// bounds where its calibration was screened, a stricter location): measured on the synthetic
/// generators and uniform sets, no right motion of gnc-tls or robin-gnc is lost by it
/// (BENCHMARK.md 40). The stand-in is not used where the set's graph would pass
/// params.max_graph_bytes (the solver searches its own rest then).
template <int Dim>
std::optional<RunnerUp> runner_up(const Solver& solver, const Correspondences<Dim>& corr,
                                  const Result<Dim>& accepted, const SolverParams& params,
                                  const Calibration& calibration, const AcceptParams& accept,
                                  const Deadline& budget, NullDraws* draws = nullptr);

/// Correspondences within this many tolerances of the accepted motion are its own (a k-NN
/// matching's neighbouring targets, a voxel away, form a near copy of the accepted set).
inline constexpr double kExplained = 2.0;
/// Runner-up motions that move the accepted inliers by at most this many tolerances (median) are
/// the accepted motion again (measured on the corpus: near copies at 0.3-2.4, aliases at 3.2-62).
inline constexpr double kSameMotion = 3.0;
/// Whether a runner-up of score `runner` is comparable to the accepted `best`: its excess over the
/// null's location mu is at least kComparable of the best's, runner - mu >= kComparable (best - mu).
/// Under the Gumbel tail log p(x) ~ -(x - mu) / beta, so this is p_runner <= p_best^kComparable.
bool comparable(int runner, int best, const NullFit& null);

/// On the corpus's KITTI negatives (FPFH) the runner-up's excess is 0.47-2.1 of the best's (RANSAC's best
/// is not always the largest); intel's true closures that have a significant alias give mostly
/// 0.07-0.2 (BENCHMARK.md section 36).
inline constexpr double kComparable = 0.4;
/// Runner-up solves per pair at most, the first included (each with its calibration, but for the
/// repeats after the first); a periodic scene's family is decided by its first two or three.
inline constexpr int kMaxRivals = 6;

inline constexpr std::uint64_t kRunnerUpStream = 0x72756e6eull;  // "runn"

}  // namespace verifybench
