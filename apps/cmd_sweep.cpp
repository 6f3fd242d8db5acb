// `verifybench sweep`: a robustness sweep on synthetic sets.
#include <algorithm>
#include <cmath>
#include <tuple>

#include "apps/cli.hpp"
#include "apps/param_options.hpp"
#include "core/registry.hpp"
#include "generators/synthetic.hpp"
#include "harness/harness.hpp"
#include "harness/progress.hpp"

namespace verifybench {

namespace {

/// Refuses an unknown generator or one that lacks a requested dimension, before any work.
void check_generator(const std::string& kind, const std::vector<int>& dims) {
  const GeneratorInfo* g = nullptr;
  try {
    g = &find_generator(kind);
  } catch (const UnknownName& e) {
    throw UsageError(std::string("--generator: ") + e.what());
  }
  for (int d : dims) {
    if ((d == 2 && !g->supports_2d) || (d == 3 && !g->supports_3d)) {
      throw UsageError("--generator " + kind + " does not exist in " + std::to_string(d) + "D");
    }
  }
}

}  // namespace

int cmd_sweep(const std::vector<std::string>& args, const std::vector<std::string>& argv) {
  SweepConfig c;
  const std::string outliers = "0.5:0.99:0.05";
  c.outlier_ratios = parse_range("--outliers", outliers, 0.0, 1.0);
  cli::SolverOptions s;
  cli::PriorOptions prior;
  Options o;
  cli::add_solver_options(o, s);
  o.group("synthetic sets")
      .bind("dim", "D", "3", "dimension: 2, 3 or 2,3",
            [&c](const std::string& v) {
              c.dims.clear();
              for (const auto& d : Options::list_value("dim", v)) {
                if (d != "2" && d != "3") throw UsageError("--dim: '" + d + "' is not 2 or 3");
                c.dims.push_back(d == "2" ? 2 : 3);
              }
            })
      .integer("n", c.n, "N", "correspondences per set", 1, 100000000)
      .bind("outliers", "RANGE", outliers,
            "outlier ratios: start:stop:step (stop included) or a,b,c",
            [&c](const std::string& v) { c.outlier_ratios = parse_range("--outliers", v, 0.0, 1.0); })
      .real("noise", c.noise, "SIGMA", "Gaussian noise per axis on inlier targets [m]", 0.0, 1e9)
      .real("extent", c.extent, "M", "side of the cube (square) the points are drawn in [m]", 1e-9,
            1e9)
      .integer("trials", c.trials, "K", "sets per (dim, outlier ratio) point", 1, 1000000)
      .flag("negatives", c.negatives,
            "each trial also draws a negative twin (the sides share no motion): the report scores "
            "accept decisions (TP, FP, TN, FN, precision, recall)")
      .text("generator", c.shape.kind, "KIND", "synthetic generator (see `verifybench list`)");
  cli::add_rows(o, synthetic_shape_rows(), c.shape);
  cli::add_prior_options(o, "each set", prior);
  cli::add_shard_option(o, c.shard);
  if (o.parse_or_help(args, "usage: verifybench sweep [options] --out FILE.json\n")) return 0;
  cli::check_solver_options(s);
  check_generator(c.shape.kind, c.dims);
  std::tie(c.prior_sigma_rot, c.prior_sigma_trans) = cli::prior_sigmas(prior);
  c.solvers = s.solvers;
  c.params = s.params;
  c.accept = s.accept;
  c.accept.resolve_runner_up(/*dense_check_runs=*/false);  // synthetic sets have no clouds
  c.seed = c.params.seed;
  c.criteria = s.criteria;
  const std::string out = cli::report_path(o, s.out);

  nlohmann::json parameters = cli::params_json(c.params, c.accept, c.criteria);
  parameters["sweep"] = {{"generator", c.shape.kind},
                         {"generator_shape", cli::rows_json(synthetic_shape_rows(), c.shape)},
                         {"prior_sigma_rot_deg", c.prior_sigma_rot * 180.0 / M_PI},
                         {"prior_sigma_trans", c.prior_sigma_trans},
                         {"dims", c.dims},
                         {"n", c.n},
                         {"outlier_ratios", c.outlier_ratios},
                         {"noise", c.noise},
                         {"extent", c.extent},
                         {"trials", c.trials},
                         {"negatives", c.negatives},
                         {"solvers", c.solvers}};
  SweepProgress point_done;
  if (!s.quiet) point_done = cli::print_point;
  Progress progress("sweep", c.shard.owned(c.units()), !s.quiet);
  const auto rows = run_sweep(c, point_done, [&] { progress.advance(); });
  // Each row's unit (SweepConfig::shard): its dim, ratio and trial, as the sweep numbered them.
  std::vector<long long> row_units;
  for (const auto& r : rows) {
    const long long d = std::find(c.dims.begin(), c.dims.end(), r.dim) - c.dims.begin();
    const long long k =
        std::find(c.outlier_ratios.begin(), c.outlier_ratios.end(), *r.outlier_ratio) -
        c.outlier_ratios.begin();
    row_units.push_back((d * static_cast<long long>(c.outlier_ratios.size()) + k) * c.trials +
                        r.trial);
  }
  return cli::finish(out, parameters, rows, argv, c.seed, cli::describe_error,
                     cli::shard_context(o, c.shard, c.units(), row_units));
}

}  // namespace verifybench
