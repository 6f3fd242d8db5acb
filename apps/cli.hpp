#pragma once
// What the commands share: the solver options (common ones here, each family's from its own
// ParamField rows), success criteria, report writing.
#include <cstdint>
#include <iostream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "apps/options.hpp"
#include "reports/record.hpp"
#include "reports/report.hpp"
#include "reports/shard.hpp"
#include "acceptance/accept_params.hpp"
#include "solvers/params.hpp"

namespace verifybench::cli {

/// What every solving command sets: --solvers, the common solver options, the accept rule, every
/// family's options (one help group each), the success criteria, --seed, --out, --quiet. The
/// values a command starts from are its defaults (--help shows them); add_solver_options binds the
/// options to these fields, check_solver_options validates them once the line is parsed.
struct SolverOptions {
  std::vector<std::string> solvers{"clique", "ransac"};
  SolverParams params;
  AcceptParams accept;
  SuccessCriteria criteria;
  std::string out;
  bool quiet = false;
  std::string out_value = "FILE.json";
  std::string out_help = "report path (required; written atomically; - for stdout)";
};
void add_solver_options(Options& o, SolverOptions& s);
/// The common solver rows named (their options), in that order: a command that needs only some of
/// them (`dimacs`: the budget; `graph`: eps and the graph's) binds the same rows, so the names,
/// defaults and ranges cannot drift.
std::vector<ParamField> common_rows(const std::vector<std::string>& options);
/// Every name against the registry (UnknownSolver lists the known ones), the solver parameters and
/// the accept rule validated (UsageError naming the key and value).
void check_solver_options(SolverOptions& s);
/// --out (required), checked before any work (check_report_path): a UsageError when it could not
/// be written; "-" is stdout (the report goes there, progress and summaries stay on stderr).
std::string report_path(const Options& o, const std::string& out);
/// The parameters block of a report: common fields, the accept rule's, every family field, the
/// success criteria.
nlohmann::json params_json(const SolverParams& p, const AcceptParams& a, const SuccessCriteria& c);

/// --prior-rot-deg / --prior-trans: a pose prior drawn around the truth.
struct PriorOptions {
  double rot_deg = 0.0;
  double trans = 0.0;
};
void add_prior_options(Options& o, const std::string& what, PriorOptions& p);
/// Both > 0 or both 0 (UsageError otherwise); radians and metres.
std::pair<double, double> prior_sigmas(const PriorOptions& p);

/// --shard I/N: run only the I-th of N slices of the work (`verifybench merge` joins them); a
/// UsageError on a malformed value; the whole work without --shard.
void add_shard_option(Options& o, Shard& shard);
/// The report's context.shard block when --shard was given, else null.
nlohmann::json shard_context(const Options& o, const Shard& shard, long long units,
                             const std::vector<long long>& row_units);

/// One summary line per aggregate of `rows` on stderr.
void print_point(const std::vector<TrialRecord>& rows);

/// The report at `out` (atomically; its path printed on stdout), or on stdout for "-".
inline void write_report(const std::string& out, const nlohmann::json& doc) {
  if (out == "-") {
    std::cout << doc.dump(2) << "\n" << std::flush;
    return;
  }
  write_json_atomic(out, doc);
  std::cout << out << "\n";
}

/// Writes the report (write_report); returns 1 when a row has status "error"
/// (its message printed by `describe`), else 0.
/// `shard` (shard_context) goes into the context when not null.
template <class Row, class Describe>
int finish(const std::string& out, const nlohmann::json& parameters, const std::vector<Row>& rows,
           const std::vector<std::string>& argv, std::uint64_t seed, Describe describe,
           const nlohmann::json& shard = nullptr) {
  nlohmann::json context = make_context(argv, seed);
  if (!shard.is_null()) context["shard"] = shard;
  write_report(out, make_report(context, parameters, rows));
  for (const auto& r : rows) {
    if (r.status == decltype(r.status)::error) {
      std::cerr << "verifybench: error: " << describe(r) << "\n";
      return 1;
    }
  }
  return 0;
}

}  // namespace verifybench::cli

namespace verifybench {
// The commands (apps/cmd_*.cpp); `argv` is the whole command line, for the report's context.
int cmd_list(const std::vector<std::string>& args);
int cmd_sweep(const std::vector<std::string>& args, const std::vector<std::string>& argv);
int cmd_run(const std::vector<std::string>& args, const std::vector<std::string>& argv);
int cmd_dimacs(const std::vector<std::string>& args, const std::vector<std::string>& argv);
int cmd_graph(const std::vector<std::string>& args, const std::vector<std::string>& argv);
int cmd_extract(const std::vector<std::string>& args);
int cmd_loop(const std::vector<std::string>& args, const std::vector<std::string>& argv);
int cmd_merge(const std::vector<std::string>& args, const std::vector<std::string>& argv);
}  // namespace verifybench

namespace verifybench::cli {
/// The error line of a failed solver row.
inline std::string describe_error(const TrialRecord& r) {
  return "solver " + r.solver + " failed: " + r.message;
}
}  // namespace verifybench::cli
