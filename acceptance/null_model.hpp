#pragma once
// The chance score of a verifier: a Gumbel law fitted to the scores it reaches on sets whose two
// sides share no motion. A maximum over many candidate sets (a clique, a consensus) is
// extreme-value distributed; the Gumbel's exponential tail is heavier than the super-exponential
// tail of clique numbers in random graphs, so the extrapolated p-values err on the side of
// rejecting.
#include <vector>

namespace verifybench {

struct NullFit {
  int draws = 0;
  double mean = 0.0, sd = 0.0;  ///< of the null scores (sd: unbiased, before the floor)
  int max = 0;                  ///< largest null score
  double location = 0.0, scale = 1.0;  ///< Gumbel mu, beta (method of moments, sd floored)

  /// P(null score >= score): the fitted tail at score - 1/2 (continuity), never below the
  /// permutation p-value (1 + #{draws >= score}) / (draws + 1) when a draw reached the score.
  double p_value(int score) const;
  /// The smallest score whose p_value is below alpha.
  int threshold(double alpha) const;

  std::vector<int> scores;  ///< the draws, in draw order
};

/// The smallest standard deviation the fit uses: K draws that all tie still leave the spread of
/// an integer score unresolved (measured on synthetic negatives, BENCHMARK.md section 14).
inline constexpr double kMinNullSd = 0.5;

/// Throws std::invalid_argument for no score or a negative one. One score fits with sd 0 (floored).
NullFit fit_null(const std::vector<int>& scores);

/// fit_null with the moments moved to the pessimistic end of what k draws allow: the mean raised
/// by 3 standard errors, the (floored) sd by its one-sided 99% chi-square bound. Its p-values are
/// above fit_null's; calibrate() accepts early only below alpha under this fit. Throws
/// std::invalid_argument for fewer than 2 scores.
NullFit cautious_fit(const std::vector<int>& scores);

/// The other end: the mean lowered by 3 standard errors, the sd by its lower 99% chi-square bound
/// (floored again). [optimistic_fit p, cautious_fit p] is the range of p that k draws cannot tell
/// apart: on scores of a known Gumbel law it holds the true tail p in 94-98% of samples of
/// k = 5-20 (tests/test_acceptance.cpp), where fit_null's p alone spans orders of magnitude.
NullFit optimistic_fit(const std::vector<int>& scores);

}  // namespace verifybench
