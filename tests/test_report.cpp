// The JSON report: schema fields, aggregates computed by hand, atomic writes.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "reports/report.hpp"

namespace verifybench {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

TrialRecord row(const std::string& solver, double ratio, double time_ms, bool success) {
  TrialRecord r;
  r.solver = solver;
  r.dataset = "synthetic";
  r.dim = 3;
  r.n = 100;
  r.outlier_ratio = ratio;
  r.noise = 0.01;
  r.status = success ? Status::ok : Status::rejected;
  r.accepted = success;
  r.time_ms = time_ms;
  r.rotation_error_deg = success ? 0.1 : 90.0;
  r.translation_error = success ? 0.01 : 3.0;
  r.success = success;
  return r;
}

TEST(Report, CarriesTheSchemaFields) {
  const std::vector<TrialRecord> rows{row("clique", 0.5, 1.0, true)};
  const json doc = make_report(make_context({"verifybench", "sweep"}, 42), {{"eps", 0.1}}, rows);
  EXPECT_EQ(doc.at("schema_version"), kReportSchemaVersion);
  for (const char* key : {"tool_version", "git_commit", "date_utc", "host", "cpu", "build_type",
                          "command_line", "seed"}) {
    EXPECT_TRUE(doc.at("context").contains(key)) << key;
  }
  EXPECT_EQ(doc["context"]["seed"], 42);
  const json& r = doc.at("results").at(0);
  for (const char* key : {"solver",
                          "dim",
                          "n",
                          "outlier_ratio",
                          "noise",
                          "status",
                          "accepted",
                          "inliers",
                          "inlier_precision",
                          "inlier_recall",
                          "inlier_f1",
                          "rotation_error_deg",
                          "translation_error",
                          "success",
                          "time_ms",
                          "graph_ms",
                          "search_ms",
                          "fit_ms",
                          "data_seed",
                          "solver_seed"}) {
    EXPECT_TRUE(r.contains(key)) << key;
  }
  EXPECT_TRUE(r["inlier_precision"].is_null());  // NaN is written as null
  for (const char* key : {"trials", "success_rate", "median_time_ms", "p90_time_ms",
                          "median_rotation_error_deg", "median_translation_error"}) {
    EXPECT_TRUE(doc.at("aggregates").at(0).contains(key)) << key;
  }
}

TEST(Report, AggregatesByHand) {
  std::vector<TrialRecord> rows;
  // clique at 0.9: times 1..10 ms, 7 successes of 10.
  for (int i = 1; i <= 10; ++i) rows.push_back(row("clique", 0.9, i, i <= 7));
  rows.push_back(row("ransac", 0.9, 5.0, false));
  const json agg = aggregate(rows);
  ASSERT_EQ(agg.size(), 2u);
  EXPECT_EQ(agg[0]["solver"], "clique");
  EXPECT_EQ(agg[0]["trials"], 10);
  EXPECT_DOUBLE_EQ(agg[0]["success_rate"].get<double>(), 0.7);
  EXPECT_DOUBLE_EQ(agg[0]["median_time_ms"].get<double>(), 5.5);  // (5 + 6) / 2
  EXPECT_DOUBLE_EQ(agg[0]["p90_time_ms"].get<double>(), 9.0);     // nearest rank ceil(0.9 * 10)
  EXPECT_DOUBLE_EQ(agg[0]["median_rotation_error_deg"].get<double>(), 0.1);
  EXPECT_DOUBLE_EQ(agg[1]["success_rate"].get<double>(), 0.0);
}

TEST(Report, SuccessRateIsNullWithoutGroundTruth) {
  TrialRecord r = row("clique", 0.5, 1.0, true);
  r.success.reset();
  r.outlier_ratio.reset();
  const json agg = aggregate({r});
  EXPECT_TRUE(agg[0]["success_rate"].is_null());
  EXPECT_TRUE(agg[0]["outlier_ratio"].is_null());
}

TEST(Report, WritesAtomicallyAndParsesBack) {
  const fs::path dir = fs::temp_directory_path() / "vb_report_test";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const fs::path file = dir / "r.json";
  const json doc =
      make_report(make_context({"x"}, 1), json::object(), {row("clique", 0.5, 1, true)});
  write_json_atomic(file.string(), doc);
  std::ifstream in(file);
  EXPECT_EQ(json::parse(in), doc);
  int entries = 0;
  for (const auto& e : fs::directory_iterator(dir)) entries += e.is_regular_file();
  EXPECT_EQ(entries, 1);  // no temporary left behind
  // An unwritable target: a clear error naming the path, and the old report untouched.
  EXPECT_THROW(write_json_atomic((dir / "missing" / "r.json").string(), doc), std::runtime_error);
  fs::create_directories(dir / "taken.json");  // a folder where the file should go
  try {
    write_json_atomic((dir / "taken.json").string(), doc);
    FAIL();
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("taken.json"), std::string::npos);
  }
  entries = 0;
  for (const auto& e : fs::directory_iterator(dir)) entries += e.is_regular_file();
  EXPECT_EQ(entries, 1);
  fs::remove_all(dir);
}

TEST(Report, NeverReplacesLinksFifosOrDevicesAndNeverFollowsAPlantedTemporary) {
  const fs::path dir = fs::temp_directory_path() / ("vb_report_paths_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  const json doc = make_report(make_context({"x"}, 1), json::object(), {row("clique", 0.5, 1, true)});
  auto slurp = [](const fs::path& p) {
    std::ifstream in(p);
    return std::string(std::istreambuf_iterator<char>(in), {});
  };
  // A symlink as the target: refused; the file it points to keeps its bytes, the link stays.
  { std::ofstream(dir / "victim") << "precious"; }
  fs::create_symlink(dir / "victim", dir / "link.json");
  EXPECT_THROW(write_json_atomic((dir / "link.json").string(), doc), std::runtime_error);
  EXPECT_EQ(slurp(dir / "victim"), "precious");
  EXPECT_TRUE(fs::is_symlink(dir / "link.json"));
  // A FIFO: refused at once (never opened, so nothing blocks), still a FIFO afterwards.
  ASSERT_EQ(::mkfifo((dir / "fifo.json").c_str(), 0600), 0);
  try {
    write_json_atomic((dir / "fifo.json").string(), doc);
    ADD_FAILURE() << "a FIFO was replaced";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("a FIFO"), std::string::npos) << e.what();
  }
  EXPECT_TRUE(fs::is_fifo(dir / "fifo.json"));
  // A character device (/dev/null exists on every Linux): refused, still a device.
  EXPECT_THROW(write_json_atomic("/dev/null", doc), std::runtime_error);
  EXPECT_TRUE(fs::is_character_file("/dev/null"));
  // Links planted at the old predictable temporary names are not followed.
  for (int pid : {::getpid(), ::getpid() + 1}) {
    fs::create_symlink(dir / "victim", dir / ("r.json.tmp." + std::to_string(pid)));
  }
  write_json_atomic((dir / "r.json").string(), doc);
  EXPECT_EQ(slurp(dir / "victim"), "precious");
  std::ifstream in(dir / "r.json");
  EXPECT_EQ(json::parse(in), doc);
  // A regular file is replaced; no temporary is left (only victim, r.json, the links, the FIFO).
  write_json_atomic((dir / "r.json").string(), doc);
  int regular = 0;
  for (const auto& e : fs::directory_iterator(dir)) regular += fs::is_regular_file(fs::symlink_status(e));
  EXPECT_EQ(regular, 2);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace verifybench
