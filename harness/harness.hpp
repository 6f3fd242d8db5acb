#pragma once
// The harness: runs solvers on correspondence sets and turns each outcome into a report row, with
// metrics from core. Used by the CLI, the tests and the benchmarks alike.
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "acceptance/verify.hpp"
#include "cliques/max_clique.hpp"
#include "core/correspondences.hpp"
#include "generators/synthetic.hpp"
#include "reports/record.hpp"
#include "reports/shard.hpp"
#include "solvers/solver.hpp"

namespace verifybench {

/// The report row of one verification (acceptance/verify.hpp), scored against `set.truth` (which
/// the solver never saw).
template <int Dim>
TrialRecord trial_record(const Verification<Dim>& verification, const std::string& solver_name,
                         const LabeledSet<Dim>& set, const SolverParams& params,
                         const SuccessCriteria& criteria);

/// verify() then trial_record(): the row of one solver on one set.
template <int Dim>
TrialRecord evaluate(const Solver& solver, const std::string& solver_name,
                     const LabeledSet<Dim>& set, const SolverParams& params,
                     const AcceptParams& accept, const SuccessCriteria& criteria);

struct SweepConfig {
  std::vector<std::string> solvers{"clique", "ransac"};
  std::vector<int> dims{3};
  int n = 500;
  std::vector<double> outlier_ratios{0.5, 0.9, 0.99};
  double noise = 0.01;
  double extent = 10.0;
  /// Generator kind and its per-kind shape; n, ratio, noise, extent and seed come from above.
  SyntheticParams shape;
  /// When both are > 0, each set carries a pose prior drawn around the truth (add_pose_prior).
  double prior_sigma_rot = 0.0;    ///< [rad]
  double prior_sigma_trans = 0.0;  ///< [m]
  int trials = 20;
  /// Each trial also draws a negative twin (SyntheticParams::negative, same kind and point), so
  /// the report scores accept decisions (TP, FP, TN, FN); negatives carry no pose prior.
  bool negatives = false;
  std::uint64_t seed = 1;
  SolverParams params;
  AcceptParams accept;
  SuccessCriteria criteria;
  /// Runs only this slice of the sets; set (dim index d, ratio index r, trial t) is unit
  /// (d * ratios + r) * trials + t.
  Shard shard;
  long long units() const {
    return static_cast<long long>(dims.size() * outlier_ratios.size()) * trials;
  }
};

/// Called after each (dim, outlier ratio) point with the rows of that point.
using SweepProgress = std::function<void(const std::vector<TrialRecord>& point_rows)>;
/// Called after each set (every solver has run on it).
using TrialProgress = std::function<void()>;

/// Every solver sees the same drawn set in each trial. The set of trial t at (dim, n, ratio) is
/// drawn from derive_seed(seed, {dim, n, ratio bits, t}), so it does not depend on which other
/// points or solvers are in the sweep; its negative twin from derive_seed(that seed, {2}). Stops at the first row whose status is "error" (returning
/// the rows so far, that one included).
std::vector<TrialRecord> run_sweep(const SweepConfig& config, const SweepProgress& progress = {},
                                   const TrialProgress& on_trial = {});

/// Runs each solver `trials` times on one set (a real dump); trial t uses solver seed
/// derive_seed(seed, {t}). With a shard, only the (solver s, trial t) pairs whose unit
/// s * trials + t it owns.
template <int Dim>
std::vector<TrialRecord> run_on_set(const std::vector<std::string>& solvers,
                                    const LabeledSet<Dim>& set, const std::string& dataset,
                                    int trials, std::uint64_t seed, const SolverParams& params,
                                    const AcceptParams& accept, const SuccessCriteria& criteria,
                                    const TrialProgress& on_trial = {}, const Shard& shard = {});

/// Runs each named clique algorithm once on `g` (DIMACS mode): one row per algorithm, its clique
/// checked (a non-clique is status "error"), 1-based ids, status ok | time_limit | unproven.
std::vector<CliqueRecord> run_clique_algorithms(const BitGraph& g, const std::string& graph_name,
                                                std::optional<int> known_omega,
                                                const std::vector<std::string>& algorithms,
                                                const CliqueSearchParams& params);

}  // namespace verifybench
