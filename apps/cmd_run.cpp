// `verifybench run`: solvers on one correspondence dump.
#include <algorithm>
#include <cmath>
#include <variant>

#include "apps/cli.hpp"
#include "datasets/dump_format.hpp"
#include "generators/synthetic.hpp"
#include "harness/harness.hpp"
#include "harness/progress.hpp"
#ifdef VERIFYBENCH_HAVE_DENSE_CHECK
#include "apps/param_options.hpp"
#include "harness/dense_rows.hpp"
#endif

namespace verifybench {

int cmd_run(const std::vector<std::string>& args, const std::vector<std::string>& argv) {
  std::string dir, expected_text = "auto";
  int trials = 1;
  cli::SolverOptions opts;
  cli::PriorOptions prior_options;
  Shard shard;
  Options o;
  o.text("dump", dir, "DIR",
         "dump folder: dump.json + matches.tsv, or corr.txt [label.txt] [GTmat.txt] (required)");
  cli::add_solver_options(o, opts);
  o.group("dump")
      .integer("trials", trials, "K", "repeat each solver K times (timing statistics)", 1, 1000000)
      .bind("expected", "E", expected_text,
            "the expected decision: positive, negative, or auto (MANIFEST.tsv beside the dump; "
            "else, where the dump has labels, positive when any label is a true inlier, negative "
            "when none is; else unknown)",
            [&expected_text](const std::string& v) {
              if (v != "auto" && v != "positive" && v != "negative") {
                throw UsageError("--expected: '" + v + "' is not positive, negative or auto");
              }
              expected_text = v;
            });
  cli::add_prior_options(o, "the set (it needs a ground truth)", prior_options);
#ifdef VERIFYBENCH_HAVE_DENSE_CHECK
  DenseCheckParams dense;
  dense.clouds = DenseCheckParams::Clouds::scans;  // a dump keeps two single scans
  o.group("dense check (dumps with clouds: extract --keep-clouds)");
  cli::add_rows(o, dense_check_param_rows(), dense);
#endif
  cli::add_shard_option(o, shard);
  if (o.parse_or_help(args, "usage: verifybench run --dump DIR [options] --out FILE.json\n"))
    return 0;
  o.require("dump");
  cli::check_solver_options(opts);
#ifdef VERIFYBENCH_HAVE_DENSE_CHECK
  dense.validate();
#endif
  const auto& names = opts.solvers;
  const SolverParams& params = opts.params;
  AcceptParams accept = opts.accept;
  const SuccessCriteria& crit = opts.criteria;
  const long long units = static_cast<long long>(names.size()) * trials;  // (solver, trial)
  const std::string out = cli::report_path(o, opts.out);
  // Named, not a structured binding: lambdas capture bindings only from C++20 (clang refuses).
  const auto prior = cli::prior_sigmas(prior_options);
  const double prior_rot = prior.first, prior_trans = prior.second;
  Dump dump = read_dump(dir);
  bool dense_runs = false;  // a dense check decides the accepted pairs (clouds, a build with it)
#ifdef VERIFYBENCH_HAVE_DENSE_CHECK
  // The report holds the threshold in force, not "the rule's default".
  if (dense.min_overlap == DenseCheckParams::kRuleDefault) {
    dense.min_overlap = dense.min_overlap_for(accept.rule);
  }
  dense_runs = dump.clouds && dense.min_overlap_for(accept.rule) > 0.0;
#endif
  // Where the clouds decide, the runner-up test is off unless asked (BENCHMARK.md section 38).
  accept.resolve_runner_up(dense_runs);
  std::optional<bool> expected;
  if (expected_text != "auto") {
    expected = expected_text == "positive";
  } else {
    expected = manifest_expected(dir);
  }
  std::vector<TrialRecord> rows = std::visit(
      [&](auto& s) {
        validate(s);
        s.truth.positive = expected;
        const auto& labels = s.truth.labels;
        if (!expected && !labels.empty()) {
          // Any true label: the sides share a motion (positive); none: they share none.
          s.truth.positive = std::find(labels.begin(), labels.end(), 1) != labels.end();
        }
        if (prior_rot > 0.0) {
          if (!s.truth.T_target_source) {
            throw UsageError("--prior-rot-deg: " + dir +
                             " has no ground truth to draw a prior around");
          }
          add_pose_prior(s, prior_rot, prior_trans, params.seed);
        }
        Progress progress("run", shard.owned(units), !opts.quiet);
        return run_on_set(
            names, s, dir, trials, params.seed, params, accept, crit, [&] { progress.advance(); },
            shard);
      },
      dump.set);
  // The dense check where the dump kept its clouds (the same check as the loop's on its maps).
  nlohmann::json dense_json = nullptr;
#ifdef VERIFYBENCH_HAVE_DENSE_CHECK
  if (dump.clouds) {
    dense_check_rows(rows, *dump.clouds, dense, accept.rule, crit);
    dense_json = cli::rows_json(dense_check_param_rows(), dense);
    dense_json["icp_max_iterations"] = dense.icp.max_iterations;
  }
#else
  if (dump.clouds && !opts.quiet) {
    std::cerr << "run: " << dir << " keeps its clouds, but this build has no dense check "
              << "(configure with the front end)\n";
  }
#endif
  if (!opts.quiet) cli::print_point(rows);
  nlohmann::json parameters = cli::params_json(params, accept, crit);
  parameters["run"] = {
      {"dump", dir},
      {"trials", trials},
      {"expected", expected_text},
      {"prior_sigma_rot_deg", prior_rot * 180.0 / M_PI},
      {"prior_sigma_trans", prior_trans},
      {"solvers", names},
      {"label_threshold",
       dump.label_threshold ? nlohmann::json(*dump.label_threshold) : nlohmann::json(nullptr)},
      {"dump_provenance", dump.provenance},
      {"clouds", dump.clouds ? nlohmann::json{{"points", {dump.clouds->source.size(),
                                                          dump.clouds->target.size()}},
                                              {"voxel_m", dump.clouds->voxel}}
                             : nlohmann::json(nullptr)},
      // null: the dump kept no clouds (or the build has no dense check), so none ran
      {"dense_check", dense_json},
      // |R^T R - I| of the ground truth as the dump published it (projected onto SO(n) for use).
      {"ground_truth_rotation_residual",
       std::visit([](const auto& s) { return s.truth.rotation_residual; }, dump.set)}};
  std::vector<long long> row_units;
  for (const auto& r : rows) {
    const long long s = std::find(names.begin(), names.end(), r.solver) - names.begin();
    row_units.push_back(s * trials + r.trial);
  }
  return cli::finish(out, parameters, rows, argv, params.seed, cli::describe_error,
                     cli::shard_context(o, shard, units, row_units));
}

}  // namespace verifybench
