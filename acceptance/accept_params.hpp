#pragma once
// How a pair is accepted as a loop closure (issue #13), apart from the solvers: `count` is the
// paper's rule (|inliers| >= K, SolverParams::min_inliers, the solver's own decision); `pvalue`
// accepts when the score beats a per-pair permutation null at level alpha (calibration.hpp), with
// the pose prior's gate where the set carries a prior (prior_gate.hpp). Applied by verify()
// (verify.hpp); the rows below are its CLI options, report keys and Python keywords.
#include <string>
#include <vector>

#include "core/param_rows.hpp"

namespace verifybench {

struct AcceptParams {
  enum class Rule { pvalue, count };
  Rule rule = Rule::pvalue;
  double alpha = 0.001;  ///< accept when p < alpha, in (0, 1)
  int null_draws = 20;   ///< permuted sets the null is fitted on, >= 2
  /// Where the range of p after null_draws draws still holds alpha (the decision other draws may
  /// reverse), draw on until it does not or this many draws ran in all; <= null_draws: never.
  int max_null_draws = 100;
  /// pvalue rule, sets with a pose prior: accept only a motion inside the prior's chi-square gate
  /// at this confidence (prior_gate.hpp), in [0, 1); 0 = no gate.
  double prior_gate = 0.999;
  /// pvalue rule: reject an accepted pair whose comparable rival motions (the same solver on what
  /// the accepted motion leaves unexplained, runner_up.hpp), each with p < this under the pair's
  /// null, hold together as many inliers as it: a rigid alias; 0 = no runner-up test.
  /// kRunnerUpDefault: `alpha` where no dense check runs, 0 where one does (resolve_runner_up()):
  /// where the clouds are known the dense check decides, and in a small scene of repeated facades
  /// true closures have rivals too (BENCHMARK.md section 38).
  double runner_up_alpha = kRunnerUpDefault;
  static constexpr double kRunnerUpDefault = -1.0;

  /// The runner-up test's level in force: runner_up_alpha, or alpha at its default (sets without
  /// clouds, which is what the solvers see) under the pvalue rule; 0 under count (no test).
  double runner_up_level() const;
  /// Fixes runner_up_alpha's default for a set whose decision does (dense_check_runs) or does not
  /// get a dense check, so the report records the level in force; an explicit value stays.
  void resolve_runner_up(bool dense_check_runs);

  /// Throws std::invalid_argument naming the field and the bad value.
  void validate() const;
};

const char* to_string(AcceptParams::Rule rule);
/// "pvalue" | "count"; throws std::invalid_argument naming the value otherwise.
AcceptParams::Rule parse_accept_rule(const std::string& name);

/// The accept rule's settings as rows (core/param_rows.hpp): --accept, --alpha, --null-draws,
/// --max-null-draws, --prior-gate, --runner-up-alpha.
const std::vector<ParamRow<AcceptParams>>& accept_param_rows();

}  // namespace verifybench
