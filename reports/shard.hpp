#pragma once
// Sharded runs (issue #17): `sweep`, `run` and `dimacs` split their work into units (a sweep's
// set at (dim, outlier ratio, trial); a dump run's (solver, trial); a DIMACS file) and
// `--shard I/N` runs the units u with u % N == I - 1: balanced round-robin slices whose sets do not
// depend on N, since each set's seed derives from its coordinates. The report of a shard carries
// context.shard = {"index": I, "count": N, "units": U, "unit_rows": [[u, rows of u], ...]}, which
// is all `verifybench merge` needs to put the rows back in the unsharded order.
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "reports/record.hpp"

namespace verifybench {

struct Shard {
  int index = 0;  ///< 0-based
  int count = 1;
  bool owns(long long unit) const { return unit % count == index; }
  /// Units of 0 .. total-1 this shard runs.
  long long owned(long long total) const {
    return total > index ? (total - index + count - 1) / count : 0;
  }
};

/// "I/N" with 1 <= I <= N (1-based, as Slurm's array ids and GNU parallel's slots count); throws
/// std::invalid_argument naming the text.
Shard parse_shard(const std::string& text);

/// The context block of a shard's report; `row_units[k]` is the unit of row k (rows of one unit
/// are consecutive).
nlohmann::json shard_block(const Shard& shard, long long units, const std::vector<long long>& row_units);

/// The inverse of to_json (NaN for null numbers, unset optionals). Throws std::invalid_argument
/// naming the field on a missing or mistyped one.
TrialRecord trial_from_json(const nlohmann::json& j);
CliqueRecord clique_from_json(const nlohmann::json& j);

/// One report from the reports of every shard of one command line: checks that all were written
/// by the same tool version and commit from the same command line (apart from --shard and --out)
/// with the same parameters, that every shard 1..N is there once and every unit once, puts the
/// rows back in the unsharded order and recomputes aggregates and decisions. `paths` name the
/// documents in messages. Throws std::invalid_argument naming the file and the field.
nlohmann::json merge_reports(const std::vector<std::string>& paths,
                             const std::vector<nlohmann::json>& docs);

/// The command line without --shard and --out (and their values), as shards are compared.
std::vector<std::string> unsharded_command_line(const std::vector<std::string>& argv);

}  // namespace verifybench
