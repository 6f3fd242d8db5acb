#pragma once
// One verification of one pair, the same wherever it is asked for (the harness's rows, the Python
// binding, the loop's candidates): the solver's search and fit, then the accept rule: the count
// rule is the solver's own decision (decide() in solvers/solver.hpp); the calibrated rule fits the
// pair's permutation null and decides on p (calibration.hpp), with the pose prior's gate where the
// set carries a prior (prior_gate.hpp). params.time_limit_s is the pair's budget: the solve takes
// what it needs of it (its own limit), and the calibrated rule's null solves share the rest
// (calibration.hpp: budget_exhausted marks a decision more time could change). The result is
// typed: the solver's Result, the calibration when there was one, the prior's d^2. The accept
// rule's settings (accept_params.hpp) are verify's alone: solvers never see them.
#include <optional>

#include "acceptance/calibration.hpp"
#include "acceptance/runner_up.hpp"
#include "solvers/solver.hpp"

namespace verifybench {

template <int Dim>
struct Verification {
  Result<Dim> result;                      ///< decision applied: accepted, status
  std::optional<Calibration> calibration;  ///< pvalue rule, when the solve did not fail
  std::optional<double> prior_d2;          ///< d^2 of the motion against the set's prior
  /// pvalue rule with runner_up_level() > 0, a pair the rest of the rule accepted: its runner-up
  std::optional<RunnerUp> runner_up;
  double solve_ms = 0.0;                   ///< the solver's own call, wall time
  AcceptParams::Rule rule = AcceptParams::Rule::pvalue;  ///< the rule that decided
};

/// Never throws for a solver's or a calibration's failure: they come back as Status::error with
/// the message.
template <int Dim>
Verification<Dim> verify(const Solver& solver, const Correspondences<Dim>& corr,
                         const SolverParams& params, const AcceptParams& accept);

}  // namespace verifybench
