#include "acceptance/verify.hpp"

#include <exception>
#include <sstream>

#include "acceptance/prior_gate.hpp"
#include "core/timer.hpp"

namespace verifybench {

template <int Dim>
Verification<Dim> verify(const Solver& solver, const Correspondences<Dim>& corr,
                         const SolverParams& params, const AcceptParams& accept) {
  Verification<Dim> v;
  v.rule = accept.rule;
  // One budget for the pair: the solve, then whatever is left for the calibrated rule's draws.
  const Deadline budget(params.time_limit_s);
  StopWatch clock;
  v.result = solver.solve(corr, params);
  v.solve_ms = clock.ms();
  if (accept.rule == AcceptParams::Rule::pvalue && v.result.status != Status::error) {
    try {
      // The null draws solved once: the runner-up test's calibrations take them again.
      NullDraws draws;
      v.calibration = calibrate(solver, corr, params, accept,
                                static_cast<int>(v.result.inliers.size()), budget, &draws);
      decide_calibrated(v.result, corr, *v.calibration, accept);
      if (v.result.accepted && accept.runner_up_level() > 0.0) {
        v.runner_up =
            runner_up(solver, corr, v.result, params, *v.calibration, accept, budget, &draws);
        if (v.runner_up && v.runner_up->ambiguous) {
          v.result.accepted = false;
          if (v.result.status == Status::ok) v.result.status = Status::rejected;
          std::ostringstream msg;
          const RunnerUp& u = *v.runner_up;
          msg << "runner-up test: " << u.rivals << (u.rivals == 1 ? " rival motion holds " : " rival motions hold ")
              << u.rival_support << " inliers against the accepted " << v.result.inliers.size()
              << " (the first: " << u.score << " inliers, p " << u.p_value << ", "
              << u.separation << " tolerances away): a rigid alias";
          v.result.message = msg.str();
        }
      }
    } catch (const std::exception& e) {
      v.calibration.reset();
      v.result.status = Status::error;
      v.result.message = e.what();
    }
  }
  if (v.result.status != Status::error) {
    v.prior_d2 = prior_distance2(corr, v.result.T_target_source);
  }
  return v;
}

template Verification<2> verify<2>(const Solver&, const Correspondences<2>&, const SolverParams&,
                                   const AcceptParams&);
template Verification<3> verify<3>(const Solver&, const Correspondences<3>&, const SolverParams&,
                                   const AcceptParams&);

}  // namespace verifybench
