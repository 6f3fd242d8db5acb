// `verifybench merge`: the reports of every shard of one `sweep`, `run` or `dimacs` command line
// (each run with --shard I/N) joined into the report the unsharded command would have written.
#include <filesystem>
#include <fstream>
#include <sstream>

#include "apps/cli.hpp"
#include "reports/shard.hpp"

namespace verifybench {

namespace {

/// A shard report is rows and metadata: far below this.
constexpr std::uintmax_t kMaxShardReportBytes = std::uintmax_t{1} << 30;

nlohmann::json read_report(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) input_error(path, 0, "not a regular file");
  const auto size = std::filesystem::file_size(path, ec);
  if (ec) input_error(path, 0, ec.message());
  if (size > kMaxShardReportBytes) {
    input_error(path, 0,
                "size " + std::to_string(size) + " bytes: over the " +
                    std::to_string(kMaxShardReportBytes >> 20) + " MiB a report may have");
  }
  std::ifstream in(path);
  if (!in) input_error(path, 0, "cannot open");
  try {
    return nlohmann::json::parse(in);
  } catch (const nlohmann::json::parse_error& e) {
    input_error(path, 0, std::string("not JSON: ") + e.what());
  }
}

}  // namespace

int cmd_merge(const std::vector<std::string>& args, const std::vector<std::string>&) {
  std::vector<std::string> files;
  std::string out;
  bool quiet = false;
  Options o;
  o.allow_positional("SHARD.json", files)
      .text("out", out, "FILE.json", "merged report path (required; written atomically; - for stdout)")
      .flag("quiet", quiet, "no summary lines");
  if (o.parse_or_help(
          args,
          "usage: verifybench merge SHARD.json... --out FILE.json\n"
          "Joins the reports of `sweep|run|dimacs ... --shard I/N` (every I of one N,\n"
          "one command line, one build) into the unsharded report: rows in the unsharded\n"
          "order, aggregates and decisions recomputed.\n"))
    return 0;
  if (files.empty()) throw UsageError("no shard report given");
  out = cli::report_path(o, out);
  std::vector<nlohmann::json> docs;
  for (const auto& path : files) docs.push_back(read_report(path));
  nlohmann::json merged;
  try {
    merged = merge_reports(files, docs);
  } catch (const std::invalid_argument& e) {
    throw InputError(e.what());
  }
  cli::write_report(out, merged);
  if (!quiet) {
    std::cerr << "merge: " << docs.size() << " shards, " << merged["results"].size() << " rows\n";
  }
  return 0;
}

}  // namespace verifybench
