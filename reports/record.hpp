#pragma once
// One row of a report: what one solver did on one correspondence set. Filled by the harness from
// a solver Result and core metrics; the report layer only serialises and summarises it.
#include <array>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "core/status.hpp"

namespace verifybench {

/// When a trial counts as a success; defaults are the 3DMatch registration-recall criteria
/// (15 deg, 30 cm) used by PointDSC, TEASER++ and MAC evaluations.
struct SuccessCriteria {
  double max_rotation_error_deg = 15.0;  ///< rotation error under this [deg]
  double max_translation_error = 0.3;    ///< translation error under this [m]
  bool requires_accepted = true;         ///< a rejected pair is never a success
};

struct TrialRecord {
  static constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

  std::string solver;
  std::string dataset;    ///< "synthetic" or the dump folder
  std::string generator;  ///< synthetic generator kind; empty for dumps
  int dim = 3;
  int n = 0;
  std::optional<double> outlier_ratio;  ///< drawn ratio (synthetic); unset for real dumps
  std::optional<double> noise;          ///< synthetic noise sigma [m]
  int trial = 0;
  std::uint64_t data_seed = 0;    ///< seed the set was drawn with (0 for dumps)
  std::uint64_t solver_seed = 0;  ///< seed handed to the solver
  Status status = Status::ok;
  std::string message;            ///< error text, empty otherwise
  bool accepted = false;
  int inliers = 0;
  std::optional<int> true_inliers;  ///< from ground-truth labels, when known
  double inlier_precision = kNaN, inlier_recall = kNaN, inlier_f1 = kNaN;  ///< NaN -> null
  double rotation_error_deg = kNaN, translation_error = kNaN;              ///< NaN -> null
  std::optional<bool> success;  ///< unset when there is no ground-truth motion
  double time_ms = 0, graph_ms = 0, search_ms = 0, fit_ms = 0;
  long long branch_nodes = 0, iterations = 0, graph_edges = 0, local_optimisations = 0;
  std::optional<int> omega_upper_bound;  ///< clique solvers: proven bound on the clique number
  // Acceptance (issue #13).
  std::string accept_rule;                 ///< pvalue | count
  std::optional<bool> expected_positive;   ///< the expected decision, when known
  double p_value = kNaN;                   ///< pvalue rule: P(chance score >= inliers)
  /// pvalue rule: the range of p the null's draws cannot tell apart (Calibration::p_value_low/high)
  double p_value_low = kNaN, p_value_high = kNaN;
  std::optional<int> null_threshold;       ///< pvalue rule: smallest score accepted at alpha
  double null_mean = kNaN, null_sd = kNaN; ///< of the null scores
  int null_draws = 0, null_limited_draws = 0;
  bool null_screened = false;  ///< pvalue rule: accepted on the score bounds, no null solve
  /// pvalue rule: the pair's time budget ran out before the draws settled the decision
  /// (Calibration::budget_exhausted), or stopped a runner-up solve that did not reject the pair
  /// (RunnerUp::time_limit): more time could change it.
  bool provisional = false;
  double calibration_ms = 0;  ///< the null solves (not in time_ms)
  std::optional<int> distinct_inliers;  ///< selection_geometry().distinct of the selected set
  double lever_arm = kNaN;              ///< selection_geometry().lever_arm [m]
  /// Sets with a pose prior: d^2 of the fitted motion under it (prior_gate.hpp); NaN -> null.
  double prior_d2 = kNaN;
  /// pvalue rule with a runner-up test, pairs the rest of the rule accepted (runner_up.hpp): the
  /// runner-up's score, its p under the pair's null, and how far its motion moves the accepted
  /// inliers (median, in tolerances); unset / NaN otherwise.
  std::optional<int> runner_up;
  double runner_up_p = kNaN, runner_up_separation = kNaN;
  bool runner_up_ambiguous = false;  ///< the runner-up test rejected the pair (RunnerUp::ambiguous)
  /// The motions that competed with the accepted one and their inliers together (RunnerUp::rivals,
  /// rival_support); unset without a runner-up test.
  std::optional<int> runner_up_rivals, runner_up_support;
  /// The dense check (acceptance/dense_check.hpp) of a pair the rule accepted, where the set's
  /// clouds are known: the clouds' overlap after ICP (NaN: it did not run), the ICP's
  /// convergence, fitness [m^2], refined motion (row-major) and the check's wall time.
  double dense_overlap = kNaN;
  bool dense_icp_converged = false;
  double dense_icp_fitness = kNaN, dense_ms = 0;
  std::vector<double> dense_T_target_source;
  std::vector<double> T_target_source;  ///< row-major (dim+1)x(dim+1) estimate
};

/// One maximum clique search on one graph (DIMACS mode).
struct CliqueRecord {
  std::string graph;  ///< file path
  std::string algorithm;
  int n = 0;
  long long edges = 0;
  SearchStatus status = SearchStatus::ok;
  std::string message;  ///< error text
  int omega = 0;        ///< size of the clique found
  std::optional<int> known_omega;  ///< from MANIFEST.tsv beside the graph, when listed
  double time_ms = 0;              ///< the search (the graph is read once, before, untimed)
  long long nodes = 0;
  int upper_bound = 0;
  long long local_search_steps = 0;  ///< bbmcx-ls, auto: steps of their local search
  std::vector<int> clique;  ///< 1-based DIMACS ids, ascending
};

}  // namespace verifybench
