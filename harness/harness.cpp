#include "harness/harness.hpp"

#include <cstring>

#include "acceptance/verify.hpp"
#include "core/metrics.hpp"
#include "core/random.hpp"
#include "core/timer.hpp"
#include "generators/synthetic.hpp"
#include "solvers/registry.hpp"

namespace verifybench {

template <int Dim>
TrialRecord trial_record(const Verification<Dim>& v, const std::string& solver_name,
                         const LabeledSet<Dim>& set, const SolverParams& params,
                         const SuccessCriteria& criteria) {
  const Result<Dim>& result = v.result;
  TrialRecord r;
  r.time_ms = v.solve_ms;
  r.accept_rule = to_string(v.rule);
  r.expected_positive = set.truth.positive;
  if (const auto& c = v.calibration) {
    r.p_value = c->p_value;
    r.p_value_low = c->p_value_low;
    r.p_value_high = c->p_value_high;
    r.null_threshold = c->threshold;
    r.null_mean = c->null.mean;
    r.null_sd = c->null.sd;
    r.null_draws = c->null.draws;
    r.null_limited_draws = c->limited_draws;
    r.null_screened = c->screened;
    r.provisional = c->budget_exhausted;
    r.calibration_ms = c->ms + (v.runner_up ? v.runner_up->ms : 0.0);
  }
  r.solver = solver_name;
  r.dim = Dim;
  r.n = static_cast<int>(set.corr.size());
  r.solver_seed = params.seed;
  r.status = result.status;
  r.message = result.message;
  r.accepted = result.accepted;
  r.inliers = static_cast<int>(result.inliers.size());
  r.graph_ms = result.times.graph_ms;
  r.search_ms = result.times.search_ms;
  r.fit_ms = result.times.fit_ms;
  r.branch_nodes = result.counters.branch_nodes;
  r.iterations = result.counters.iterations;
  r.graph_edges = result.counters.graph_edges;
  r.local_optimisations = result.counters.local_optimisations;
  r.omega_upper_bound = result.omega_upper_bound;
  const Eigen::Matrix<double, Dim + 1, Dim + 1> M = result.T_target_source.matrix();
  for (int i = 0; i <= Dim; ++i) {
    for (int j = 0; j <= Dim; ++j) r.T_target_source.push_back(M(i, j));
  }
  if (result.status == Status::error) return r;
  const SelectionGeometry geometry = selection_geometry(set.corr, result.inliers);
  r.distinct_inliers = geometry.distinct;
  r.lever_arm = geometry.lever_arm;
  if (v.prior_d2) r.prior_d2 = *v.prior_d2;
  if (const auto& u = v.runner_up) {
    r.runner_up = u->score;
    r.runner_up_p = u->p_value;
    r.runner_up_separation = u->separation;
    r.runner_up_ambiguous = u->ambiguous;
    r.runner_up_rivals = u->rivals;
    r.runner_up_support = u->rival_support;
    // A runner-up the budget cut short may have been a larger one: more time could reject.
    r.provisional = r.provisional || (u->time_limit && !u->ambiguous);
  }

  if (!set.truth.labels.empty()) {
    const InlierScores s = inlier_scores(result.inliers, set.truth.labels);
    r.inlier_precision = s.precision;
    r.inlier_recall = s.recall;
    r.inlier_f1 = s.f1;
    r.true_inliers =
        static_cast<int>(std::count(set.truth.labels.begin(), set.truth.labels.end(), 1));
  }
  if (set.truth.T_target_source) {
    r.rotation_error_deg = rotation_error_deg(result.T_target_source, *set.truth.T_target_source);
    r.translation_error = translation_error(result.T_target_source, *set.truth.T_target_source);
    r.success = (!criteria.requires_accepted || result.accepted) &&
                r.rotation_error_deg < criteria.max_rotation_error_deg &&
                r.translation_error < criteria.max_translation_error;
  }
  return r;
}

template <int Dim>
TrialRecord evaluate(const Solver& solver, const std::string& solver_name,
                     const LabeledSet<Dim>& set, const SolverParams& params,
                     const AcceptParams& accept, const SuccessCriteria& criteria) {
  return trial_record(verify(solver, set.corr, params, accept), solver_name, set, params, criteria);
}

namespace {

std::uint64_t bits_of(double v) {
  std::uint64_t b;
  std::memcpy(&b, &v, sizeof b);
  return b;
}

template <int Dim>
void sweep_point(const SweepConfig& config, double ratio, long long first_unit,
                 std::vector<TrialRecord>& rows, const TrialProgress& on_trial) {
  std::vector<std::unique_ptr<Solver>> solvers;
  for (const auto& name : config.solvers) solvers.push_back(SolverRegistry::create(name));
  for (int t = 0; t < config.trials; ++t) {
    if (!config.shard.owns(first_unit + t)) continue;
    SyntheticParams sp = config.shape;
    sp.n = config.n;
    sp.outlier_ratio = ratio;
    sp.noise = config.noise;
    sp.extent = config.extent;
    sp.max_translation = config.extent / 2;
    sp.seed = derive_seed(config.seed, {std::uint64_t(Dim), std::uint64_t(config.n), bits_of(ratio),
                                        std::uint64_t(t)});
    std::vector<LabeledSet<Dim>> sets{make_synthetic<Dim>(sp)};
    if (config.prior_sigma_rot > 0.0 && config.prior_sigma_trans > 0.0) {
      add_pose_prior(sets[0], config.prior_sigma_rot, config.prior_sigma_trans, sp.seed);
    }
    std::vector<std::uint64_t> seeds{sp.seed};
    if (config.negatives) {
      SyntheticParams np = sp;
      np.negative = true;
      np.seed = derive_seed(sp.seed, {2});
      sets.push_back(make_synthetic<Dim>(np));
      seeds.push_back(np.seed);
    }
    for (std::size_t k = 0; k < sets.size(); ++k) {
      SolverParams params = config.params;
      params.seed = derive_seed(seeds[k], {1});
      for (std::size_t s = 0; s < solvers.size(); ++s) {
        TrialRecord r = evaluate(*solvers[s], config.solvers[s], sets[k], params, config.accept,
                                 config.criteria);
        r.dataset = "synthetic";
        r.generator = sp.kind;
        r.outlier_ratio = ratio;
        r.noise = config.noise;
        r.trial = t;
        r.data_seed = seeds[k];
        rows.push_back(std::move(r));
        if (rows.back().status == Status::error) return;
      }
    }
    if (on_trial) on_trial();
  }
}

}  // namespace

std::vector<TrialRecord> run_sweep(const SweepConfig& config, const SweepProgress& progress,
                                   const TrialProgress& on_trial) {
  std::vector<TrialRecord> rows;
  long long unit = 0;
  for (int dim : config.dims) {
    for (double ratio : config.outlier_ratios) {
      std::vector<TrialRecord> point;
      if (dim == 2)
        sweep_point<2>(config, ratio, unit, point, on_trial);
      else
        sweep_point<3>(config, ratio, unit, point, on_trial);
      unit += config.trials;
      if (progress && !point.empty()) progress(point);
      const bool failed = !point.empty() && point.back().status == Status::error;
      rows.insert(rows.end(), point.begin(), point.end());
      if (failed) return rows;
    }
  }
  return rows;
}

template <int Dim>
std::vector<TrialRecord> run_on_set(const std::vector<std::string>& solvers,
                                    const LabeledSet<Dim>& set, const std::string& dataset,
                                    int trials, std::uint64_t seed, const SolverParams& params,
                                    const AcceptParams& accept, const SuccessCriteria& criteria,
                                    const TrialProgress& on_trial, const Shard& shard) {
  std::vector<TrialRecord> rows;
  for (std::size_t s = 0; s < solvers.size(); ++s) {
    const std::string& name = solvers[s];
    const auto solver = SolverRegistry::create(name);
    for (int t = 0; t < trials; ++t) {
      if (!shard.owns(static_cast<long long>(s) * trials + t)) continue;
      SolverParams p = params;
      p.seed = derive_seed(seed, {std::uint64_t(t)});
      TrialRecord r = evaluate(*solver, name, set, p, accept, criteria);
      r.dataset = dataset;
      r.trial = t;
      rows.push_back(std::move(r));
      if (on_trial) on_trial();
    }
  }
  return rows;
}

std::vector<CliqueRecord> run_clique_algorithms(const BitGraph& g, const std::string& graph_name,
                                                std::optional<int> known_omega,
                                                const std::vector<std::string>& algorithms,
                                                const CliqueSearchParams& params) {
  std::vector<CliqueRecord> rows;
  for (const auto& name : algorithms) {
    const auto& algorithm = CliqueAlgorithms::get(name);
    CliqueRecord r;
    r.graph = graph_name;
    r.algorithm = name;
    r.n = g.size();
    r.edges = g.edge_count();
    r.known_omega = known_omega;
    try {
      StopWatch clock;
      const CliqueSearchResult res = algorithm.run(g, params);
      r.time_ms = clock.ms();
      r.status = res.stopped   ? SearchStatus::time_limit
                 : res.optimal ? SearchStatus::ok
                               : SearchStatus::unproven;
      r.omega = static_cast<int>(res.clique.size());
      r.nodes = res.nodes;
      r.upper_bound = res.upper_bound;
      r.local_search_steps = res.local_search_steps;
      for (int v : res.clique) r.clique.push_back(v + 1);
      if (!g.is_clique(res.clique)) {
        r.status = SearchStatus::error;
        r.message = "the returned vertex set is not a clique";
      }
    } catch (const std::exception& e) {
      r.status = SearchStatus::error;
      r.message = e.what();
    }
    rows.push_back(std::move(r));
  }
  return rows;
}

template TrialRecord trial_record<2>(const Verification<2>&, const std::string&,
                                     const LabeledSet<2>&, const SolverParams&,
                                     const SuccessCriteria&);
template TrialRecord trial_record<3>(const Verification<3>&, const std::string&,
                                     const LabeledSet<3>&, const SolverParams&,
                                     const SuccessCriteria&);
template TrialRecord evaluate<2>(const Solver&, const std::string&, const LabeledSet<2>&,
                                 const SolverParams&, const AcceptParams&, const SuccessCriteria&);
template TrialRecord evaluate<3>(const Solver&, const std::string&, const LabeledSet<3>&,
                                 const SolverParams&, const AcceptParams&, const SuccessCriteria&);
template std::vector<TrialRecord> run_on_set<2>(const std::vector<std::string>&,
                                                const LabeledSet<2>&, const std::string&, int,
                                                std::uint64_t, const SolverParams&,
                                                const AcceptParams&, const SuccessCriteria&,
                                                const TrialProgress&,
                                                const Shard&);
template std::vector<TrialRecord> run_on_set<3>(const std::vector<std::string>&,
                                                const LabeledSet<3>&, const std::string&, int,
                                                std::uint64_t, const SolverParams&,
                                                const AcceptParams&, const SuccessCriteria&,
                                                const TrialProgress&,
                                                const Shard&);

}  // namespace verifybench
