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
  Options o;
  cli::add_solver_options(o);
  o.group("synthetic sets")
      .add("dim", "D", "3", "dimension: 2, 3 or 2,3")
      .add("n", "N", "500", "correspondences per set")
      .add("outliers", "RANGE", "0.5:0.99:0.05",
           "outlier ratios: start:stop:step (stop included) or a,b,c")
      .add("noise", "SIGMA", "0.01", "Gaussian noise per axis on inlier targets [m]")
      .add("extent", "M", "10", "side of the cube (square) the points are drawn in [m]")
      .add("trials", "K", "20", "sets per (dim, outlier ratio) point")
      .add("negatives", "", "",
           "each trial also draws a negative twin (the sides share no motion): the report scores "
           "accept decisions (TP, FP, TN, FN, precision, recall)")
      .add("generator", "KIND", "uniform", "synthetic generator (see `verifybench list`)");
  cli::add_rows(o, synthetic_shape_rows(), SyntheticParams{});
  cli::add_prior_options(o, "each set");
  cli::add_shard_option(o);
  if (o.parse_or_help(args, "usage: verifybench sweep [options] --out FILE.json\n")) return 0;
  SweepConfig c;
  c.solvers = cli::solver_names(o);
  c.dims.clear();
  for (const auto& d : o.list("dim")) {
    if (d != "2" && d != "3") throw UsageError("--dim: '" + d + "' is not 2 or 3");
    c.dims.push_back(d == "2" ? 2 : 3);
  }
  c.n = static_cast<int>(o.integer("n", 1, 100000000));
  c.outlier_ratios = parse_range("--outliers", o.text("outliers"), 0.0, 1.0);
  c.noise = o.real("noise", 0.0, 1e9);
  c.extent = o.real("extent", 1e-9, 1e9);
  c.trials = static_cast<int>(o.integer("trials", 1, 1000000));
  c.negatives = o.flag("negatives");
  c.shape.kind = o.text("generator");
  cli::read_rows(o, synthetic_shape_rows(), c.shape);
  check_generator(c.shape.kind, c.dims);
  std::tie(c.prior_sigma_rot, c.prior_sigma_trans) = cli::prior_sigmas(o);
  c.params = cli::solver_params(o);
  c.accept = cli::accept_params(o);
  c.seed = c.params.seed;
  c.criteria = cli::criteria(o);
  c.shard = cli::shard(o);
  const std::string out = cli::report_path(o);

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
  if (!o.flag("quiet")) point_done = cli::print_point;
  Progress progress("sweep", c.shard.owned(c.units()), !o.flag("quiet"));
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
                     cli::shard_context(o, c.units(), row_units));
}

}  // namespace verifybench
