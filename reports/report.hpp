#pragma once
// Versioned JSON reports. Layout (schema_version 1):
//   { "schema_version": 1, "context": {...}, "parameters": {...},
//     "results": [TrialRecord...], "aggregates": [per solver x setting summaries],
//     "decisions": [per solver accept-decision scores] }
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "reports/record.hpp"

namespace verifybench {

inline constexpr int kReportSchemaVersion = 1;

/// Tool version, git commit, UTC date, host, CPU, build type, command line and seed.
nlohmann::json make_context(const std::vector<std::string>& command_line, std::uint64_t seed);

nlohmann::json to_json(const TrialRecord& row);

/// Groups rows by (solver, dataset, dim, n, outlier_ratio, noise, expected) and summarises each
/// group: trials, accept_rate, success_rate (null without ground truth), median and p90 time, median
/// errors, median calibration time, decision counts. Medians average the two middle values; p90 is the nearest-rank percentile.
nlohmann::json aggregate(const std::vector<TrialRecord>& rows);

/// "TP" | "FP" | "TN" | "FN" for a row whose expected decision is known (error rows: none).
const char* decision_of(const TrialRecord& row);

/// Per solver over every row with an expected decision: tp, fp, tn, fn, precision, recall, f1,
/// false_accept_rate (null where a ratio has no denominator).
nlohmann::json decisions(const std::vector<TrialRecord>& rows);

nlohmann::json make_report(const nlohmann::json& context, const nlohmann::json& parameters,
                           const std::vector<TrialRecord>& rows);

/// DIMACS mode: `correct` is omega == known_omega for a proven result, omega <= known_omega for an
/// unproven one, null when unknown. Aggregates per algorithm: graphs, proven, correct, total and
/// median time.
nlohmann::json to_json(const CliqueRecord& row);
nlohmann::json make_report(const nlohmann::json& context, const nlohmann::json& parameters,
                           const std::vector<CliqueRecord>& rows);

/// Throws std::runtime_error naming the path when a report could not be written there: the path
/// exists and is not a regular file (a symlink, FIFO, device, directory or socket is never
/// replaced), or its folder is missing or not writable. Commands call it before doing the work.
void check_report_path(const std::string& path);

/// Writes to an exclusively created PATH.tmp.XXXXXX beside the target (mkstemp), fsyncs it and
/// renames it over PATH, so a reader never sees half a report. check_report_path() first. Throws
/// std::runtime_error naming the path on failure and leaves no temporary file behind.
void write_json_atomic(const std::string& path, const nlohmann::json& doc);
/// The same for any text (markdown tables, TSV).
void write_text_atomic(const std::string& path, const std::string& text);

}  // namespace verifybench
