#include "apps/cli.hpp"

#include <cmath>
#include <cstdio>

#include "apps/param_options.hpp"
#include "solvers/registry.hpp"

namespace verifybench::cli {

void add_solver_options(Options& o, const SolverOptionDefaults& d) {
  o.group("solvers").add("solvers", "A,B", "clique,ransac",
                         "solvers to run (see `verifybench list`)");
  add_rows(o, common_param_family().fields, d.params);
  o.group("accept rule");
  add_rows(o, accept_param_rows(), d.accept);
  for (const ParamFamily& family : param_families()) {
    o.group(family.title);
    add_rows(o, family.fields, d.params);
  }
  o.group("success, reproducibility, output")
      .add("success-rot-deg", "DEG", "15", "success: rotation error under this [deg]")
      .add("success-trans", "M", "0.3", "success: translation error under this [m]")
      .add("seed", "S", "1", "seed of every random draw (recorded in the report)")
      .add("out", d.out_value, "", d.out_help)
      .add("quiet", "", "", "no progress lines");
}

SolverParams solver_params(const Options& o, const SolverParams& defaults) {
  SolverParams p = defaults;
  read_rows(o, solver_param_rows(), p);
  p.seed = o.seed("seed");
  try {
    p.validate();
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  }
  return p;
}

AcceptParams accept_params(const Options& o, const AcceptParams& defaults) {
  AcceptParams a = defaults;
  read_rows(o, accept_param_rows(), a);
  try {
    a.validate();
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  }
  return a;
}

SuccessCriteria criteria(const Options& o) {
  SuccessCriteria c;
  c.max_rotation_error_deg = o.real("success-rot-deg", 0, 180);
  c.max_translation_error = o.real("success-trans", 0, 1e12);
  return c;
}

std::string report_path(const Options& o) {
  const std::string out = o.required("out");
  if (out == "-") return out;  // the report on stdout
  try {
    check_report_path(out);
  } catch (const std::runtime_error& e) {
    throw UsageError(std::string("--out: ") + e.what());
  }
  return out;
}

std::vector<std::string> solver_names(const Options& o) {
  const auto names = o.list("solvers");
  SolverRegistry::check(names);
  return names;
}

nlohmann::json params_json(const SolverParams& p, const AcceptParams& a, const SuccessCriteria& c) {
  nlohmann::json j = rows_json(solver_param_rows(), p);
  j.update(rows_json(accept_param_rows(), a));
  j["accept_threshold_2d"] = p.accept_threshold(2);
  j["accept_threshold_3d"] = p.accept_threshold(3);
  j["success_criteria"] = {{"max_rotation_error_deg", c.max_rotation_error_deg},
                           {"max_translation_error", c.max_translation_error},
                           {"requires_accepted", c.requires_accepted}};
  return j;
}

void add_prior_options(Options& o, const std::string& what) {
  o.add("prior-rot-deg", "DEG", "0",
        "give " + what +
            " a pose prior drawn around the truth: rotation sigma per axis [deg] (with "
            "--prior-trans; jcbb uses it)")
      .add("prior-trans", "M", "0", "pose prior translation sigma per axis [m]");
}

std::pair<double, double> prior_sigmas(const Options& o) {
  const double rot = o.real("prior-rot-deg", 0.0, 180.0) * M_PI / 180.0;
  const double trans = o.real("prior-trans", 0.0, 1e9);
  if ((rot > 0.0) != (trans > 0.0)) {
    throw UsageError("--prior-rot-deg and --prior-trans go together (both > 0)");
  }
  return {rot, trans};
}

void print_point(const std::vector<TrialRecord>& rows) {
  for (const auto& a : aggregate(rows)) {
    const std::string expected =
        a["expected"].is_null() ? "" : " (" + a["expected"].get<std::string>() + ")";
    std::fprintf(stderr, "  %dD n=%d outliers=%s%s %-8s success=%s accept=%.2f median=%.2f ms\n",
                 a["dim"].get<int>(), a["n"].get<int>(), a["outlier_ratio"].dump().c_str(),
                 expected.c_str(), a["solver"].get<std::string>().c_str(),
                 a["success_rate"].dump().c_str(), a["accept_rate"].get<double>(),
                 a["median_time_ms"].is_null() ? 0.0 : a["median_time_ms"].get<double>());
  }
}

void add_shard_option(Options& o) {
  o.group("sharding")
      .add("shard", "I/N", "",
           "run only the I-th of N deterministic, balanced slices of the work (1 <= I <= N); "
           "`verifybench merge` joins the N reports into the unsharded one");
}

Shard shard(const Options& o) {
  if (!o.given("shard")) return Shard{};
  try {
    return parse_shard(o.text("shard"));
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  }
}

nlohmann::json shard_context(const Options& o, long long units,
                             const std::vector<long long>& row_units) {
  if (!o.given("shard")) return nullptr;
  return shard_block(shard(o), units, row_units);
}

}  // namespace verifybench::cli
