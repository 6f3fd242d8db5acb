#include "apps/cli.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "apps/param_options.hpp"
#include "solvers/registry.hpp"

namespace verifybench::cli {

void add_solver_options(Options& o, SolverOptions& s) {
  o.group("solvers").list("solvers", s.solvers, "A,B", "solvers to run (see `verifybench list`)");
  add_rows(o, common_param_family().fields, s.params);
  o.group("accept rule");
  add_rows(o, accept_param_rows(), s.accept);
  for (const ParamFamily& family : param_families()) {
    o.group(family.title);
    add_rows(o, family.fields, s.params);
  }
  o.group("success, reproducibility, output")
      .real("success-rot-deg", s.criteria.max_rotation_error_deg, "DEG",
            "success: rotation error under this [deg]", 0, 180)
      .real("success-trans", s.criteria.max_translation_error, "M",
            "success: translation error under this [m]", 0, 1e12)
      .seed("seed", s.params.seed, "seed of every random draw (recorded in the report)")
      .text("out", s.out, s.out_value, s.out_help)
      .flag("quiet", s.quiet, "no progress lines");
}

std::vector<ParamField> common_rows(const std::vector<std::string>& options) {
  std::vector<ParamField> rows;
  for (const std::string& option : options) {
    const auto& all = common_param_family().fields;
    const auto it = std::find_if(all.begin(), all.end(),
                                 [&](const ParamField& f) { return f.option == option; });
    if (it == all.end()) throw std::logic_error("no common solver row --" + option);
    rows.push_back(*it);
  }
  return rows;
}

void check_solver_options(SolverOptions& s) {
  SolverRegistry::check(s.solvers);
  try {
    s.params.validate();
    s.accept.validate();
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  }
}

std::string report_path(const Options& o, const std::string& out) {
  o.require("out");
  if (out == "-") return out;  // the report on stdout
  try {
    check_report_path(out);
  } catch (const std::runtime_error& e) {
    throw UsageError(std::string("--out: ") + e.what());
  }
  return out;
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

void add_prior_options(Options& o, const std::string& what, PriorOptions& p) {
  o.real("prior-rot-deg", p.rot_deg, "DEG",
         "give " + what +
             " a pose prior drawn around the truth: rotation sigma per axis [deg] (with "
             "--prior-trans; jcbb uses it)",
         0.0, 180.0)
      .real("prior-trans", p.trans, "M", "pose prior translation sigma per axis [m]", 0.0, 1e9);
}

std::pair<double, double> prior_sigmas(const PriorOptions& p) {
  if ((p.rot_deg > 0.0) != (p.trans > 0.0)) {
    throw UsageError("--prior-rot-deg and --prior-trans go together (both > 0)");
  }
  return {p.rot_deg * M_PI / 180.0, p.trans};
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

void add_shard_option(Options& o, Shard& shard) {
  o.group("sharding").bind(
      "shard", "I/N", "",
      "run only the I-th of N deterministic, balanced slices of the work (1 <= I <= N); "
      "`verifybench merge` joins the N reports into the unsharded one",
      [&shard](const std::string& v) {
        try {
          shard = parse_shard(v);
        } catch (const std::invalid_argument& e) {
          throw UsageError(e.what());
        }
      });
}

nlohmann::json shard_context(const Options& o, const Shard& shard, long long units,
                             const std::vector<long long>& row_units) {
  if (!o.given("shard")) return nullptr;
  return shard_block(shard, units, row_units);
}

}  // namespace verifybench::cli
