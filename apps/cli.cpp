#include "apps/cli.hpp"

#include <cmath>
#include <cstdio>

#include "solvers/registry.hpp"

namespace verifybench::cli {

void add_solver_options(Options& o, const SolverOptionDefaults& d) {
  o.group("solvers")
      .add("solvers", "A,B", "clique,ransac", "solvers to run (see `verifybench list`)")
      .add("eps", "M", d.eps, "pair length tolerance of the correspondence graph, Eq. (1) [m]")
      .add("inlier-threshold", "M", "", "consensus residual threshold [m] (default: eps)")
      .add("accept", "RULE", "pvalue",
           "accept rule: pvalue (p < alpha against a permutation null of the pair) or count "
           "(inliers >= --min-inliers, the paper's rule)")
      .add("alpha", "A", "0.001", "pvalue rule: accept when p < A")
      .add("null-draws", "K", "20",
           "pvalue rule: permuted sets the null is fitted on (each one more solve)")
      .add("max-null-draws", "K", "100",
           "pvalue rule: where the range of p after --null-draws draws still holds alpha, draw on "
           "until it does not or K draws ran in all (<= --null-draws: never)")
      .add("prior-gate", "C", "0.999",
           "pvalue rule, sets with a pose prior: accept only motions inside the prior's "
           "chi-square gate at confidence C (0 = no gate)")
      .add("min-inliers", "K", "0",
           "count rule: accept when inliers >= K; 0 = paper default (5 in 3D, 10 in 2D)")
      .add("time-limit", "S", "60",
           "the pair's time budget [s]: the solve, then the pvalue rule's null solves share what "
           "is left (a decision the budget cut short is marked provisional); best-so-far past it")
      .add("max-graph-mb", "MB", "4096", "refuse correspondence graphs larger than this")
      .add("threads", "T", "1",
           "threads for graph construction and clique-bbmc-dec (0 = all cores); results do not "
           "depend on it");
  for (const ParamFamily& family : param_families()) {
    o.group(family.title);
    for (const ParamField& f : family.fields) {
      o.add(f.option, f.value_name, default_text(f), f.help);
    }
  }
  o.group("success, reproducibility, output")
      .add("success-rot-deg", "DEG", "15", "success: rotation error under this [deg]")
      .add("success-trans", "M", "0.3", "success: translation error under this [m]")
      .add("seed", "S", "1", "seed of every random draw (recorded in the report)")
      .add("out", d.out_value, "", d.out_help)
      .add("quiet", "", "", "no progress lines");
}

SolverParams solver_params(const Options& o) {
  SolverParams p;
  p.eps = o.real("eps", 1e-12, 1e12);
  p.inlier_threshold =
      o.given("inlier-threshold") ? o.real("inlier-threshold", 1e-12, 1e12) : p.eps;
  p.min_inliers = static_cast<int>(o.integer("min-inliers", 0, 1 << 30));
  try {
    p.accept.rule = parse_accept_rule(o.text("accept"));
  } catch (const std::invalid_argument& e) {
    throw UsageError(std::string("--accept: ") + e.what());
  }
  p.accept.alpha = o.real("alpha", 1e-300, 0.999999);
  p.accept.null_draws = static_cast<int>(o.integer("null-draws", 2, 100000));
  p.accept.max_null_draws = static_cast<int>(o.integer("max-null-draws", 0, 100000));
  p.accept.prior_gate = o.real("prior-gate", 0.0, 0.999999999);
  p.time_limit_s = o.real("time-limit", 1e-6, 1e9);
  p.max_graph_bytes = static_cast<std::size_t>(o.integer("max-graph-mb", 1, 1LL << 30)) << 20;
  p.seed = o.seed("seed");
  p.threads = static_cast<int>(o.integer("threads", 0, 1024));
  for (const ParamFamily& family : param_families()) {
    for (const ParamField& f : family.fields) {
      switch (f.kind) {
        case ParamField::Kind::flag:
          f.set(p, o.flag(f.option) ? 1.0 : 0.0);
          break;
        case ParamField::Kind::integer:
          f.set(p, static_cast<double>(o.integer(f.option, static_cast<long long>(f.min),
                                                 static_cast<long long>(f.max))));
          break;
        case ParamField::Kind::real:
          f.set(p, o.real(f.option, f.min, f.max));
          break;
      }
    }
  }
  p.validate();
  return p;
}

SuccessCriteria criteria(const Options& o) {
  SuccessCriteria c;
  c.max_rotation_error_deg = o.real("success-rot-deg", 0, 180);
  c.max_translation_error = o.real("success-trans", 0, 1e12);
  return c;
}

std::string report_path(const Options& o) {
  const std::string out = o.required("out");
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

nlohmann::json params_json(const SolverParams& p, const SuccessCriteria& c) {
  nlohmann::json j = {{"eps", p.eps},
                      {"inlier_threshold", p.inlier_threshold},
                      {"accept_rule", to_string(p.accept.rule)},
                      {"alpha", p.accept.alpha},
                      {"null_draws", p.accept.null_draws},
                      {"max_null_draws", p.accept.max_null_draws},
                      {"prior_gate", p.accept.prior_gate},
                      {"min_inliers", p.min_inliers},
                      {"accept_threshold_2d", p.accept_threshold(2)},
                      {"accept_threshold_3d", p.accept_threshold(3)},
                      {"time_limit_s", p.time_limit_s},
                      {"max_graph_bytes", p.max_graph_bytes},
                      {"threads", p.threads}};
  for (const ParamFamily& family : param_families()) {
    for (const ParamField& f : family.fields) {
      const double v = f.report ? f.report(p) : f.get(p);
      switch (f.kind) {
        case ParamField::Kind::flag:
          j[f.key] = v != 0.0;
          break;
        case ParamField::Kind::integer:
          j[f.key] = static_cast<long long>(v);
          break;
        case ParamField::Kind::real:
          j[f.key] = v;
          break;
      }
    }
  }
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
                 a["success_rate"].dump().c_str(),
                 a["accept_rate"].get<double>(),
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

nlohmann::json shard_context(const Options& o, long long units, const std::vector<long long>& row_units) {
  if (!o.given("shard")) return nullptr;
  return shard_block(shard(o), units, row_units);
}

}  // namespace verifybench::cli
