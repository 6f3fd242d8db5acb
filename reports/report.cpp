#include "reports/report.hpp"

#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <fstream>
#include <map>
#include <stdexcept>
#include <thread>
#include <tuple>

#include "verifybench/version.hpp"

namespace verifybench {

namespace {

using nlohmann::json;

json number_or_null(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }

std::string utc_now() {
  const std::time_t now = std::time(nullptr);
  std::tm tm{};
  gmtime_r(&now, &tm);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return buf;
}

std::string cpu_model() {
  std::ifstream in("/proc/cpuinfo");
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind("model name", 0) == 0) {
      const auto colon = line.find(':');
      if (colon != std::string::npos) return line.substr(line.find_first_not_of(" \t", colon + 1));
    }
  }
  return "unknown";
}

std::string host_name() {
  char buf[256] = {};
  return gethostname(buf, sizeof buf - 1) == 0 ? std::string(buf) : "unknown";
}

/// Sorted copy of the finite values.
std::vector<double> finite_sorted(const std::vector<double>& values) {
  std::vector<double> v;
  for (double x : values) {
    if (std::isfinite(x)) v.push_back(x);
  }
  std::sort(v.begin(), v.end());
  return v;
}

json median(const std::vector<double>& values) {
  const auto v = finite_sorted(values);
  if (v.empty()) return nullptr;
  const std::size_t mid = v.size() / 2;
  return v.size() % 2 ? v[mid] : 0.5 * (v[mid - 1] + v[mid]);
}

json percentile_nearest_rank(const std::vector<double>& values, double p) {
  const auto v = finite_sorted(values);
  if (v.empty()) return nullptr;
  const auto rank = static_cast<std::size_t>(std::ceil(p / 100.0 * double(v.size())));
  return v[std::clamp<std::size_t>(rank, 1, v.size()) - 1];
}

}  // namespace

json make_context(const std::vector<std::string>& command_line, std::uint64_t seed) {
  return {{"tool", "verifybench"},
          {"tool_version", kVersion},
          {"git_commit", kGitCommit},
          {"build_type", kBuildType},
          {"compiler", __VERSION__},
          {"date_utc", utc_now()},
          {"host", host_name()},
          {"cpu", cpu_model()},
          {"hardware_threads", std::thread::hardware_concurrency()},
          {"command_line", command_line},
          {"seed", seed}};
}

const char* decision_of(const TrialRecord& r) {
  if (!r.expected_positive || r.status == Status::error) return nullptr;
  if (*r.expected_positive) return r.accepted ? "TP" : "FN";
  return r.accepted ? "FP" : "TN";
}

namespace {

struct DecisionCounts {
  int tp = 0, fp = 0, tn = 0, fn = 0;
  void add(const TrialRecord& r) {
    const char* d = decision_of(r);
    if (!d) return;
    const std::string s = d;
    tp += s == "TP";
    fp += s == "FP";
    tn += s == "TN";
    fn += s == "FN";
  }
  json to_json() const {
    auto ratio = [](int a, int b) { return b > 0 ? json(double(a) / b) : json(nullptr); };
    const json precision = ratio(tp, tp + fp), recall = ratio(tp, tp + fn);
    json f1 = nullptr;
    if (tp > 0) f1 = 2.0 * tp / (2.0 * tp + fp + fn);
    else if (tp + fp + fn > 0) f1 = 0.0;
    return {{"tp", tp},         {"fp", fp},       {"tn", tn},
            {"fn", fn},         {"precision", precision}, {"recall", recall},
            {"f1", f1},
            {"false_accept_rate", ratio(fp, fp + tn)}};
  }
};

}  // namespace

json decisions(const std::vector<TrialRecord>& rows) {
  std::map<std::string, DecisionCounts> by_solver;
  std::vector<std::string> order;
  for (const auto& r : rows) {
    if (!decision_of(r)) continue;
    if (!by_solver.count(r.solver)) order.push_back(r.solver);
    by_solver[r.solver].add(r);
  }
  json out = json::array();
  for (const auto& name : order) {
    json j = by_solver[name].to_json();
    j["solver"] = name;
    out.push_back(std::move(j));
  }
  return out;
}

json to_json(const TrialRecord& r) {
  json j = {{"solver", r.solver},
            {"dataset", r.dataset},
            {"generator", r.generator.empty() ? json(nullptr) : json(r.generator)},
            {"dim", r.dim},
            {"n", r.n},
            {"outlier_ratio", r.outlier_ratio ? json(*r.outlier_ratio) : json(nullptr)},
            {"noise", r.noise ? json(*r.noise) : json(nullptr)},
            {"trial", r.trial},
            {"data_seed", r.data_seed},
            {"solver_seed", r.solver_seed},
            {"status", to_string(r.status)},
            {"accepted", r.accepted},
            {"inliers", r.inliers},
            {"true_inliers", r.true_inliers ? json(*r.true_inliers) : json(nullptr)},
            {"inlier_precision", number_or_null(r.inlier_precision)},
            {"inlier_recall", number_or_null(r.inlier_recall)},
            {"inlier_f1", number_or_null(r.inlier_f1)},
            {"rotation_error_deg", number_or_null(r.rotation_error_deg)},
            {"translation_error", number_or_null(r.translation_error)},
            {"success", r.success ? json(*r.success) : json(nullptr)},
            {"time_ms", r.time_ms},
            {"graph_ms", r.graph_ms},
            {"search_ms", r.search_ms},
            {"fit_ms", r.fit_ms},
            {"branch_nodes", r.branch_nodes},
            {"iterations", r.iterations},
            {"graph_edges", r.graph_edges},
            {"local_optimisations", r.local_optimisations},
            {"omega_upper_bound", r.omega_upper_bound ? json(*r.omega_upper_bound) : json(nullptr)},
            {"accept_rule", r.accept_rule},
            {"expected", r.expected_positive ? json(*r.expected_positive ? "positive" : "negative")
                                             : json(nullptr)},
            {"decision", decision_of(r) ? json(decision_of(r)) : json(nullptr)},
            {"p_value", number_or_null(r.p_value)},
            {"p_value_range", std::isnan(r.p_value_low) ? json(nullptr)
                                                        : json::array({r.p_value_low, r.p_value_high})},
            {"null_threshold", r.null_threshold ? json(*r.null_threshold) : json(nullptr)},
            {"null_mean", number_or_null(r.null_mean)},
            {"null_sd", number_or_null(r.null_sd)},
            {"null_draws", r.null_draws},
            {"null_limited_draws", r.null_limited_draws},
            {"null_screened", r.null_screened},
            {"provisional", r.provisional},
            {"calibration_ms", r.calibration_ms},
            {"distinct_inliers", r.distinct_inliers ? json(*r.distinct_inliers) : json(nullptr)},
            {"lever_arm", number_or_null(r.lever_arm)},
            {"prior_d2", number_or_null(r.prior_d2)},
            {"runner_up", r.runner_up ? json(*r.runner_up) : json(nullptr)},
            {"runner_up_p", number_or_null(r.runner_up_p)},
            {"runner_up_separation", number_or_null(r.runner_up_separation)},
            {"runner_up_ambiguous", r.runner_up_ambiguous},
            {"runner_up_rivals", r.runner_up_rivals ? json(*r.runner_up_rivals) : json(nullptr)},
            {"runner_up_support", r.runner_up_support ? json(*r.runner_up_support) : json(nullptr)},
            {"dense_check", std::isnan(r.dense_overlap)
                                ? json(nullptr)
                                : json{{"overlap", r.dense_overlap},
                                       {"icp_converged", r.dense_icp_converged},
                                       {"icp_fitness_m2", number_or_null(r.dense_icp_fitness)},
                                       {"ms", r.dense_ms},
                                       {"T_target_source_refined", r.dense_T_target_source}}},
            {"T_target_source", r.T_target_source}};
  if (!r.message.empty()) j["message"] = r.message;
  return j;
}

json aggregate(const std::vector<TrialRecord>& rows) {
  using Key = std::tuple<std::string, std::string, std::string, int, int, double, double, int>;
  auto opt = [](const std::optional<double>& v) { return v ? *v : -1.0; };
  auto expected = [](const TrialRecord& r) { return r.expected_positive ? int(*r.expected_positive) : -1; };
  std::map<Key, std::vector<const TrialRecord*>> groups;
  std::vector<Key> first_seen;  // keep the rows' order in the output
  for (const auto& r : rows) {
    Key key{r.solver, r.dataset, r.generator, r.dim, r.n, opt(r.outlier_ratio), opt(r.noise),
            expected(r)};
    auto& g = groups[key];
    if (g.empty()) first_seen.push_back(key);
    g.push_back(&r);
  }
  json out = json::array();
  for (const Key& key : first_seen) {
    const auto& g = groups[key];
    const TrialRecord& head = *g.front();
    std::vector<double> times, rot, trans, inliers, calibration;
    DecisionCounts counts;
    int accepted = 0, judged = 0, succeeded = 0, errors = 0, limited = 0;
    for (const TrialRecord* r : g) {
      times.push_back(r->time_ms);
      rot.push_back(r->rotation_error_deg);
      trans.push_back(r->translation_error);
      inliers.push_back(r->inliers);
      accepted += r->accepted;
      calibration.push_back(r->calibration_ms);
      counts.add(*r);
      errors += r->status == Status::error;
      limited += r->status == Status::time_limit;
      if (r->success) {
        ++judged;
        succeeded += *r->success;
      }
    }
    out.push_back(
        {{"solver", head.solver},
         {"dataset", head.dataset},
         {"generator", head.generator.empty() ? json(nullptr) : json(head.generator)},
         {"dim", head.dim},
         {"n", head.n},
         {"outlier_ratio", head.outlier_ratio ? json(*head.outlier_ratio) : json(nullptr)},
         {"noise", head.noise ? json(*head.noise) : json(nullptr)},
         {"trials", g.size()},
         {"errors", errors},
         {"time_limited", limited},
         {"accept_rate", double(accepted) / double(g.size())},
         {"success_rate", judged ? json(double(succeeded) / judged) : json(nullptr)},
         {"median_time_ms", median(times)},
         {"p90_time_ms", percentile_nearest_rank(times, 90.0)},
         {"median_inliers", median(inliers)},
         {"median_rotation_error_deg", median(rot)},
         {"median_translation_error", median(trans)},
         {"expected", head.expected_positive
                          ? json(*head.expected_positive ? "positive" : "negative")
                          : json(nullptr)},
         {"median_calibration_ms", median(calibration)},
         {"decisions", counts.to_json()}});
  }
  return out;
}

json make_report(const json& context, const json& parameters,
                 const std::vector<TrialRecord>& rows) {
  json results = json::array();
  for (const auto& r : rows) results.push_back(to_json(r));
  return {{"schema_version", kReportSchemaVersion},
          {"context", context},
          {"parameters", parameters},
          {"results", std::move(results)},
          {"aggregates", aggregate(rows)},
          {"decisions", decisions(rows)}};
}

namespace {
// Correct only where proved: a proved row is right when its omega is the known one; a row that
// ran out of time (or a heuristic's) is wrong only when it claims more than the known omega, and
// else says nothing (null), even when its clique happens to be a maximum one.
json correctness(const CliqueRecord& r) {
  if (!r.known_omega || r.status == SearchStatus::error) return nullptr;
  if (r.status == SearchStatus::ok) return r.omega == *r.known_omega;
  return r.omega > *r.known_omega ? json(false) : json(nullptr);
}

bool found_unproved(const CliqueRecord& r) {
  return r.known_omega && r.status != SearchStatus::ok && r.status != SearchStatus::error &&
         r.omega == *r.known_omega;
}
}  // namespace

json to_json(const CliqueRecord& r) {
  json j = {{"graph", r.graph},
            {"algorithm", r.algorithm},
            {"n", r.n},
            {"edges", r.edges},
            {"status", to_string(r.status)},
            {"omega", r.omega},
            {"known_omega", r.known_omega ? json(*r.known_omega) : json(nullptr)},
            {"correct", correctness(r)},
            {"time_ms", r.time_ms},
            {"nodes", r.nodes},
            {"upper_bound", r.upper_bound},
            {"clique", r.clique}};
  if (r.local_search_steps > 0) j["local_search_steps"] = r.local_search_steps;
  if (!r.message.empty()) j["message"] = r.message;
  return j;
}

json make_report(const json& context, const json& parameters,
                 const std::vector<CliqueRecord>& rows) {
  json results = json::array(), aggregates = json::array();
  std::vector<std::string> order;
  std::map<std::string, std::vector<const CliqueRecord*>> by_algorithm;
  for (const auto& r : rows) {
    results.push_back(to_json(r));
    if (by_algorithm[r.algorithm].empty()) order.push_back(r.algorithm);
    by_algorithm[r.algorithm].push_back(&r);
  }
  for (const auto& name : order) {
    int proven = 0, correct = 0, wrong = 0, found = 0;
    double total = 0;
    std::vector<double> times;
    for (const CliqueRecord* r : by_algorithm[name]) {
      proven += r->status == SearchStatus::ok;
      const json c = correctness(*r);
      correct += c == true;
      wrong += c == false;
      found += found_unproved(*r);
      total += r->time_ms;
      times.push_back(r->time_ms);
    }
    aggregates.push_back({{"algorithm", name},
                          {"graphs", by_algorithm[name].size()},
                          {"proven", proven},
                          {"correct", correct},
                          {"found_unproved", found},
                          {"wrong", wrong},
                          {"total_time_ms", total},
                          {"median_time_ms", median(times)}});
  }
  return {{"schema_version", kReportSchemaVersion},
          {"context", context},
          {"parameters", parameters},
          {"results", std::move(results)},
          {"aggregates", std::move(aggregates)}};
}

void check_report_path(const std::string& path) {
  if (path.empty()) throw std::runtime_error("cannot write report: the path is empty");
  struct stat st {};
  if (::lstat(path.c_str(), &st) == 0) {
    const char* what = S_ISLNK(st.st_mode)    ? "a symbolic link"
                       : S_ISDIR(st.st_mode)  ? "a directory"
                       : S_ISFIFO(st.st_mode) ? "a FIFO"
                       : S_ISCHR(st.st_mode) || S_ISBLK(st.st_mode) ? "a device"
                       : S_ISSOCK(st.st_mode) ? "a socket"
                       : S_ISREG(st.st_mode)  ? nullptr
                                              : "not a regular file";
    if (what) {
      throw std::runtime_error("cannot write report " + path + ": it is " + what +
                               "; reports only replace regular files");
    }
  } else if (errno != ENOENT) {
    throw std::runtime_error("cannot write report " + path + ": " + std::strerror(errno));
  }
  const std::string dir = [&] {
    const auto slash = path.find_last_of('/');
    return slash == std::string::npos ? std::string(".") : path.substr(0, slash + 1);
  }();
  if (::access(dir.c_str(), W_OK | X_OK) != 0) {
    throw std::runtime_error("cannot write report " + path + ": folder " + dir + ": " +
                             std::strerror(errno));
  }
}

void write_json_atomic(const std::string& path, const json& doc) {
  write_text_atomic(path, doc.dump(2) + "\n");
}

void write_text_atomic(const std::string& path, const std::string& text) {
  check_report_path(path);
  // A fresh, exclusively created temporary beside the target (mkstemp: O_CREAT | O_EXCL, so a link
  // planted at a guessable name is never followed), written, flushed to disk, then renamed.
  std::string tmp = path + ".tmp.XXXXXX";
  const int fd = ::mkstemp(tmp.data());
  if (fd < 0) {
    throw std::runtime_error("cannot write report " + path + ": " + std::strerror(errno));
  }
  auto fail = [&](const std::string& why) {
    ::close(fd);
    ::unlink(tmp.c_str());
    throw std::runtime_error("cannot write report " + path + ": " + why);
  };
  for (std::size_t done = 0; done < text.size();) {
    const ssize_t k = ::write(fd, text.data() + done, text.size() - done);
    if (k < 0) {
      if (errno == EINTR) continue;
      fail(std::strerror(errno));
    }
    done += static_cast<std::size_t>(k);
  }
  if (::fchmod(fd, 0644) != 0 || ::fsync(fd) != 0) fail(std::strerror(errno));
  if (::close(fd) != 0) {
    const std::string why = std::strerror(errno);
    ::unlink(tmp.c_str());
    throw std::runtime_error("cannot write report " + path + ": " + why);
  }
  check_report_path(path);  // the target may have been swapped while we wrote
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    const std::string why = std::strerror(errno);
    ::unlink(tmp.c_str());
    throw std::runtime_error("cannot write report " + path + ": " + why);
  }
}

}  // namespace verifybench
