// `verifybench dimacs`: maximum clique algorithms on DIMACS graphs, checked against MANIFEST.tsv.
#include <cstdio>
#include <filesystem>
#include <optional>

#include "apps/cli.hpp"
#include "apps/param_options.hpp"
#include "cliques/max_clique.hpp"
#include "datasets/dimacs.hpp"
#include "harness/harness.hpp"
#include "harness/progress.hpp"

namespace verifybench {

int cmd_dimacs(const std::vector<std::string>& args, const std::vector<std::string>& argv) {
  // The solvers' rows of the time budget, threads and graph cap (solvers/params.cpp): one search
  // a graph is one "pair".
  const std::vector<ParamField> budget_rows =
      cli::common_rows({"time-limit", "threads", "max-graph-mb"});
  std::vector<std::string> files, names{kDefaultCliqueAlgorithm};
  SolverParams solver;
  CliqueSearchParams params;
  std::string out;
  bool quiet = false;
  Shard shard;  // one unit per file
  Options o;
  o.allow_positional("FILE.clq", files)
      .list("algorithms", names, "A,B", "clique algorithms (see `verifybench list`)");
  cli::add_rows(o, budget_rows, solver);
  o.seed("seed", params.seed, "seed of the randomised algorithms (bbmcx-ls; recorded in the report)")
      .text("out", out, "FILE.json", "report path (required; written atomically; - for stdout)")
      .flag("quiet", quiet, "no progress lines");
  cli::add_shard_option(o, shard);
  if (o.parse_or_help(
          args,
          "usage: verifybench dimacs FILE.clq... [options] --out FILE.json\n"
          "Known clique numbers are taken from MANIFEST.tsv beside each file when present.\n"))
    return 0;
  if (files.empty()) throw UsageError("no DIMACS file given");
  for (const auto& n : names) CliqueAlgorithms::get(n);  // throws with the known names
  params.time_limit_s = solver.time_limit_s;
  params.threads = solver.threads;
  const std::size_t max_bytes = solver.max_graph_bytes;
  const long long units = static_cast<long long>(files.size());
  out = cli::report_path(o, out);

  std::vector<CliqueRecord> rows;
  std::vector<long long> row_units;
  Progress progress("dimacs", shard.owned(units) * static_cast<long long>(names.size()),
                    !quiet);
  for (long long unit = 0; unit < units; ++unit) {
    if (!shard.owns(unit)) continue;
    const std::string& file = files[static_cast<std::size_t>(unit)];
    const BitGraph g = read_dimacs(file, max_bytes);
    const std::filesystem::path path(file);
    std::optional<int> known;
    const auto manifest = path.parent_path() / "MANIFEST.tsv";
    if (std::filesystem::exists(manifest)) {
      const auto omega = read_manifest(manifest.string());
      const auto it = omega.find(path.stem().string());
      if (it != omega.end()) known = it->second;
    }
    for (CliqueRecord& r : run_clique_algorithms(g, file, known, names, params)) {
      progress.advance(1, path.filename().string() + " " + r.algorithm +
                              " omega=" + std::to_string(r.omega) +
                              " known=" + (known ? std::to_string(*known) : "-") + " " + to_string(r.status) +
                              " " + std::to_string(r.time_ms) + " ms");
      rows.push_back(std::move(r));
      row_units.push_back(unit);
    }
  }
  const nlohmann::json parameters = {{"mode", "dimacs"},
                                     {"algorithms", names},
                                     {"time_limit_s", params.time_limit_s},
                                     {"threads", params.threads},
                                     {"seed", params.seed}};
  return cli::finish(
      out, parameters, rows, argv, params.seed,
      [](const CliqueRecord& r) { return r.algorithm + " on " + r.graph + ": " + r.message; },
      cli::shard_context(o, shard, units, row_units));
}

}  // namespace verifybench
