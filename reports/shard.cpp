#include "reports/shard.hpp"

#include <cmath>
#include <map>
#include <stdexcept>

#include "reports/report.hpp"

namespace verifybench {

namespace {

using nlohmann::json;

[[noreturn]] void bad(const std::string& what) { throw std::invalid_argument(what); }

const json& field(const json& j, const char* key) {
  if (!j.is_object() || !j.contains(key)) bad(std::string("field '") + key + "' missing");
  return j.at(key);
}

template <class T>
T get(const json& j, const char* key) {
  const json& v = field(j, key);
  try {
    return v.get<T>();
  } catch (const json::exception&) {
    bad(std::string("field '") + key + "': unexpected value " + v.dump());
  }
}

double real_or_nan(const json& j, const char* key) {
  if (!j.contains(key) || j.at(key).is_null()) return TrialRecord::kNaN;
  if (!j.at(key).is_number()) bad(std::string("field '") + key + "': not a number: " + j.at(key).dump());
  return j.at(key).get<double>();
}

template <class T>
std::optional<T> optional(const json& j, const char* key) {
  if (!j.contains(key) || j.at(key).is_null()) return std::nullopt;
  return get<T>(j, key);
}

/// The "status" field as its enum; an unknown name is refused with its value.
template <class E>
E status_field(const json& j) {
  const std::string name = get<std::string>(j, "status");
  const auto status = status_from_name<E>(name);
  if (!status) bad("field 'status': unknown status '" + name + "'");
  return *status;
}

std::string text_or_empty(const json& j, const char* key) {
  return j.contains(key) && !j.at(key).is_null() ? get<std::string>(j, key) : std::string();
}

}  // namespace

Shard parse_shard(const std::string& text) {
  const auto slash = text.find('/');
  auto number = [&](const std::string& s) -> long long {
    if (s.empty() || s.size() > 9 || s.find_first_not_of("0123456789") != std::string::npos) return -1;
    return std::stoll(s);
  };
  const long long i = slash == std::string::npos ? -1 : number(text.substr(0, slash));
  const long long n = slash == std::string::npos ? -1 : number(text.substr(slash + 1));
  if (i < 1 || n < 1 || i > n) {
    bad("--shard: '" + text + "' is not I/N with 1 <= I <= N (e.g. 2/8: the second of 8 slices)");
  }
  return Shard{static_cast<int>(i - 1), static_cast<int>(n)};
}

json shard_block(const Shard& shard, long long units, const std::vector<long long>& row_units) {
  json unit_rows = json::array();
  for (std::size_t k = 0; k < row_units.size();) {
    std::size_t end = k;
    while (end < row_units.size() && row_units[end] == row_units[k]) ++end;
    unit_rows.push_back({row_units[k], end - k});
    k = end;
  }
  return {{"index", shard.index + 1}, {"count", shard.count}, {"units", units},
          {"unit_rows", std::move(unit_rows)}};
}

TrialRecord trial_from_json(const json& j) {
  TrialRecord r;
  r.solver = get<std::string>(j, "solver");
  r.dataset = get<std::string>(j, "dataset");
  r.generator = text_or_empty(j, "generator");
  r.dim = get<int>(j, "dim");
  r.n = get<int>(j, "n");
  r.outlier_ratio = optional<double>(j, "outlier_ratio");
  r.noise = optional<double>(j, "noise");
  r.trial = get<int>(j, "trial");
  r.data_seed = get<std::uint64_t>(j, "data_seed");
  r.solver_seed = get<std::uint64_t>(j, "solver_seed");
  r.status = status_field<Status>(j);
  r.message = text_or_empty(j, "message");
  r.accepted = get<bool>(j, "accepted");
  r.inliers = get<int>(j, "inliers");
  r.true_inliers = optional<int>(j, "true_inliers");
  r.inlier_precision = real_or_nan(j, "inlier_precision");
  r.inlier_recall = real_or_nan(j, "inlier_recall");
  r.inlier_f1 = real_or_nan(j, "inlier_f1");
  r.rotation_error_deg = real_or_nan(j, "rotation_error_deg");
  r.translation_error = real_or_nan(j, "translation_error");
  r.success = optional<bool>(j, "success");
  r.time_ms = get<double>(j, "time_ms");
  r.graph_ms = get<double>(j, "graph_ms");
  r.search_ms = get<double>(j, "search_ms");
  r.fit_ms = get<double>(j, "fit_ms");
  r.branch_nodes = get<long long>(j, "branch_nodes");
  r.iterations = get<long long>(j, "iterations");
  r.graph_edges = get<long long>(j, "graph_edges");
  r.local_optimisations = get<long long>(j, "local_optimisations");
  r.omega_upper_bound = optional<int>(j, "omega_upper_bound");
  r.accept_rule = get<std::string>(j, "accept_rule");
  if (const auto e = optional<std::string>(j, "expected")) {
    if (*e != "positive" && *e != "negative") bad("field 'expected': unexpected value \"" + *e + "\"");
    r.expected_positive = *e == "positive";
  }
  r.p_value = real_or_nan(j, "p_value");
  if (j.contains("p_value_range") && !j.at("p_value_range").is_null()) {  // absent before it existed
    const json& range = j.at("p_value_range");
    if (!range.is_array() || range.size() != 2 || !range[0].is_number() || !range[1].is_number()) {
      bad("field 'p_value_range': not two numbers: " + range.dump());
    }
    r.p_value_low = range[0].get<double>();
    r.p_value_high = range[1].get<double>();
  }
  r.null_threshold = optional<int>(j, "null_threshold");
  r.null_mean = real_or_nan(j, "null_mean");
  r.null_sd = real_or_nan(j, "null_sd");
  r.null_draws = get<int>(j, "null_draws");
  r.null_limited_draws = get<int>(j, "null_limited_draws");
  r.null_screened = optional<bool>(j, "null_screened").value_or(false);  // absent before it existed
  r.provisional = optional<bool>(j, "provisional").value_or(false);      // absent before it existed
  r.calibration_ms = get<double>(j, "calibration_ms");
  r.distinct_inliers = optional<int>(j, "distinct_inliers");
  r.lever_arm = real_or_nan(j, "lever_arm");
  r.prior_d2 = real_or_nan(j, "prior_d2");  // absent (before it existed) or null: no prior
  r.runner_up = optional<int>(j, "runner_up");  // absent before it existed
  r.runner_up_p = real_or_nan(j, "runner_up_p");
  r.runner_up_separation = real_or_nan(j, "runner_up_separation");
  r.runner_up_ambiguous = optional<bool>(j, "runner_up_ambiguous").value_or(false);
  r.runner_up_rivals = optional<int>(j, "runner_up_rivals");  // absent before it existed
  r.runner_up_support = optional<int>(j, "runner_up_support");
  if (j.contains("dense_check") && !j.at("dense_check").is_null()) {  // absent before it existed
    const json& d = j.at("dense_check");
    if (!d.is_object()) bad("field 'dense_check': not an object: " + d.dump());
    r.dense_overlap = get<double>(d, "overlap");
    r.dense_icp_converged = get<bool>(d, "icp_converged");
    r.dense_icp_fitness = real_or_nan(d, "icp_fitness_m2");
    r.dense_ms = get<double>(d, "ms");
    r.dense_T_target_source = get<std::vector<double>>(d, "T_target_source_refined");
  }
  const json& T = field(j, "T_target_source");
  if (!T.is_array()) bad("field 'T_target_source': not an array");
  for (const json& v : T) {
    if (!v.is_null() && !v.is_number()) bad("field 'T_target_source': not a number: " + v.dump());
    r.T_target_source.push_back(v.is_null() ? TrialRecord::kNaN : v.get<double>());
  }
  return r;
}

CliqueRecord clique_from_json(const json& j) {
  CliqueRecord r;
  r.graph = get<std::string>(j, "graph");
  r.algorithm = get<std::string>(j, "algorithm");
  r.n = get<int>(j, "n");
  r.edges = get<long long>(j, "edges");
  r.status = status_field<SearchStatus>(j);
  r.message = text_or_empty(j, "message");
  r.omega = get<int>(j, "omega");
  r.known_omega = optional<int>(j, "known_omega");
  r.time_ms = get<double>(j, "time_ms");
  r.nodes = get<long long>(j, "nodes");
  r.upper_bound = get<int>(j, "upper_bound");
  r.local_search_steps = j.contains("local_search_steps") ? get<long long>(j, "local_search_steps") : 0;
  r.clique = get<std::vector<int>>(j, "clique");
  return r;
}

std::vector<std::string> unsharded_command_line(const std::vector<std::string>& argv) {
  std::vector<std::string> out;
  for (std::size_t k = 0; k < argv.size(); ++k) {
    const std::string& a = argv[k];
    if (a == "--shard" || a == "--out") {
      ++k;  // and its value
      continue;
    }
    if (a.rfind("--shard=", 0) == 0 || a.rfind("--out=", 0) == 0) continue;
    out.push_back(a);
  }
  return out;
}

json merge_reports(const std::vector<std::string>& paths, const std::vector<json>& docs) {
  if (docs.empty()) bad("merge: no report given");
  struct Part {
    std::size_t doc;
    std::size_t first_row, rows;
  };
  std::map<int, std::size_t> shard_of;   // index -> document
  std::map<long long, Part> unit_parts;  // unit -> rows
  int count = 0;
  long long units = 0;
  std::vector<std::string> command;
  bool cliques = false;
  for (std::size_t d = 0; d < docs.size(); ++d) {
    const json& doc = docs[d];
    const std::string& name = paths[d];
    try {
      if (!doc.is_object() || get<int>(doc, "schema_version") != kReportSchemaVersion) {
        bad("field 'schema_version': expected " + std::to_string(kReportSchemaVersion));
      }
      const json& context = field(doc, "context");
      if (!context.contains("shard")) bad("field 'context.shard' missing: not a shard's report (run it with --shard I/N)");
      const json& shard = context.at("shard");
      const int index = get<int>(shard, "index");
      const int n = get<int>(shard, "count");
      const long long u = get<long long>(shard, "units");
      const auto line = unsharded_command_line(get<std::vector<std::string>>(context, "command_line"));
      const std::vector<std::string> args(line.begin() + (line.empty() ? 0 : 1), line.end());
      const json& results = field(doc, "results");
      if (!results.is_array()) bad("field 'results': not an array");
      const bool is_clique = !results.empty() && results[0].contains("algorithm");
      if (d == 0) {
        count = n;
        units = u;
        command = args;
        cliques = is_clique;
      } else {
        const json& first = docs[0].at("context");
        if (n != count) bad("context.shard.count " + std::to_string(n) + " differs from " + paths[0] + "'s " + std::to_string(count));
        for (const char* key : {"tool_version", "git_commit"}) {
          if (context.value(key, json()) != first.value(key, json())) {
            bad(std::string("context.") + key + " " + context.value(key, json()).dump() + " differs from " +
                paths[0] + "'s " + first.value(key, json()).dump() + ": shards of different builds");
          }
        }
        if (args != command) bad("context.command_line differs from " + paths[0] + "'s (apart from --shard and --out): shards of different runs");
        if (doc.value("parameters", json()) != docs[0].value("parameters", json())) {
          bad("field 'parameters' differs from " + paths[0] + "'s");
        }
        if (u != units) bad("context.shard.units " + std::to_string(u) + " differs from " + paths[0] + "'s " + std::to_string(units));
        if (!results.empty() && is_clique != cliques) bad("rows of another kind than " + paths[0] + "'s");
      }
      if (n < 1 || index < 1 || index > n) bad("context.shard: index " + std::to_string(index) + " of " + std::to_string(n));
      const auto [it, fresh] = shard_of.emplace(index, d);
      if (!fresh) bad("shard " + std::to_string(index) + "/" + std::to_string(n) + " given twice (also " + paths[it->second] + ")");
      std::size_t row = 0;
      for (const json& entry : field(shard, "unit_rows")) {
        if (!entry.is_array() || entry.size() != 2 || !entry[0].is_number_integer() || !entry[1].is_number_integer()) {
          bad("context.shard.unit_rows: expected [unit, rows] pairs, got " + entry.dump());
        }
        const long long unit = entry[0].get<long long>();
        const long long k = entry[1].get<long long>();
        if (unit < 0 || unit >= u || unit % n != index - 1) {
          bad("context.shard.unit_rows: unit " + std::to_string(unit) + " is not one of shard " + std::to_string(index) + "/" + std::to_string(n) + "'s");
        }
        if (k < 0 || row + static_cast<std::size_t>(k) > results.size()) bad("context.shard.unit_rows: more rows than 'results' holds");
        if (!unit_parts.emplace(unit, Part{d, row, static_cast<std::size_t>(k)}).second) {
          bad("context.shard.unit_rows: unit " + std::to_string(unit) + " listed twice");
        }
        row += static_cast<std::size_t>(k);
      }
      if (row != results.size()) bad("context.shard.unit_rows accounts for " + std::to_string(row) + " of " + std::to_string(results.size()) + " rows");
    } catch (const std::invalid_argument& e) {
      bad(name + ": " + e.what());
    }
  }
  for (int i = 1; i <= count; ++i) {
    if (!shard_of.count(i)) bad("merge: shard " + std::to_string(i) + "/" + std::to_string(count) + " missing");
  }
  for (long long u = 0; u < units; ++u) {
    if (!unit_parts.count(u)) {
      bad("merge: unit " + std::to_string(u) + " of shard " + std::to_string(u % count + 1) + "/" +
          std::to_string(count) + " has no rows (" + paths[shard_of[int(u % count) + 1]] +
          " stopped early at an error?)");
    }
  }
  json context = docs[0].at("context");
  context.erase("shard");
  std::vector<std::string> line = unsharded_command_line(context.at("command_line").get<std::vector<std::string>>());
  context["command_line"] = line;
  context["merged_from"] = paths;
  context["shards"] = count;
  const json& parameters = docs[0].at("parameters");
  auto rows_of = [&](auto from_json) {
    std::vector<decltype(from_json(json()))> rows;
    for (const auto& [unit, part] : unit_parts) {
      const json& results = docs[part.doc].at("results");
      for (std::size_t k = part.first_row; k < part.first_row + part.rows; ++k) {
        try {
          rows.push_back(from_json(results[k]));
        } catch (const std::invalid_argument& e) {
          bad(paths[part.doc] + ": results[" + std::to_string(k) + "]: " + e.what());
        }
      }
    }
    return rows;
  };
  if (cliques) return make_report(context, parameters, rows_of([](const json& j) { return clique_from_json(j); }));
  return make_report(context, parameters, rows_of([](const json& j) { return trial_from_json(j); }));
}

}  // namespace verifybench
