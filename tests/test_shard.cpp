// Sharded runs and `verifybench merge` (issue #17): slices are disjoint, cover the work and are
// balanced (checked by enumeration); a merged report equals the unsharded one row for row apart
// from times, for sweep, run and dimacs; a slice's sets do not depend on the number of shards;
// shards of different runs, missing or repeated shards are refused naming the file.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <random>
#include <set>

#include "generators/synthetic.hpp"
#include "reports/report.hpp"
#include "reports/shard.hpp"
#include "test_util.hpp"

namespace vb = verifybench;
namespace fs = std::filesystem;
using nlohmann::json;
using vb::test::run_cli;

namespace {

json load(const fs::path& p) {
  std::ifstream in(p);
  return json::parse(in);
}

/// A row or aggregate without its wall-clock fields (the only ones a rerun may change).
json without_times(json j) {
  for (const char* key : {"time_ms", "graph_ms", "search_ms", "fit_ms", "calibration_ms",
                          "median_time_ms", "p90_time_ms", "median_calibration_ms", "total_time_ms"}) {
    j.erase(key);
  }
  return j;
}

void expect_same_report(const json& whole, const json& merged) {
  ASSERT_EQ(whole["results"].size(), merged["results"].size());
  for (std::size_t k = 0; k < whole["results"].size(); ++k) {
    EXPECT_EQ(without_times(whole["results"][k]), without_times(merged["results"][k])) << "row " << k;
  }
  ASSERT_EQ(whole["aggregates"].size(), merged["aggregates"].size());
  for (std::size_t k = 0; k < whole["aggregates"].size(); ++k) {
    EXPECT_EQ(without_times(whole["aggregates"][k]), without_times(merged["aggregates"][k]))
        << "aggregate " << k;
  }
  EXPECT_EQ(whole.value("decisions", json()), merged.value("decisions", json()));
  EXPECT_EQ(whole["parameters"], merged["parameters"]);
  // The merged report's command line is the shards' one without --shard and --out.
  EXPECT_EQ(json(vb::unsharded_command_line(whole["context"]["command_line"])),
            merged["context"]["command_line"]);
}

fs::path fresh_dir(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

/// Runs `command` unsharded and as N shards (given to merge in reverse order); returns both.
std::pair<json, json> whole_and_merged(const fs::path& dir, const std::string& command, int n) {
  const auto whole = run_cli(command + " --quiet --out " + (dir / "whole.json").string());
  EXPECT_EQ(whole.code, 0) << whole.output;
  std::string shards;
  for (int i = n; i >= 1; --i) {
    const fs::path part = dir / ("part" + std::to_string(i) + ".json");
    const auto r = run_cli(command + " --quiet --shard " + std::to_string(i) + "/" +
                           std::to_string(n) + " --out " + part.string());
    EXPECT_EQ(r.code, 0) << r.output;
    shards += " " + part.string();
  }
  const auto m = run_cli("merge" + shards + " --out " + (dir / "merged.json").string());
  EXPECT_EQ(m.code, 0) << m.output;
  return {load(dir / "whole.json"), load(dir / "merged.json")};
}

}  // namespace

TEST(Shard, ParseAcceptsOnlyIOverNWithinRange) {
  const vb::Shard s = vb::parse_shard("2/8");
  EXPECT_EQ(s.index, 1);
  EXPECT_EQ(s.count, 8);
  for (const char* bad : {"0/3", "4/3", "1/0", "3", "a/b", "-1/3", "1/3/4", "/3", "1/", " 1/3", "1/1e3"}) {
    EXPECT_THROW(vb::parse_shard(bad), std::invalid_argument) << bad;
  }
}

TEST(Shard, SlicesAreDisjointCoverEverythingAndAreBalanced) {
  for (int n : {1, 2, 3, 7}) {
    for (long long units : {0LL, 1LL, 5LL, 21LL, 100LL}) {
      std::vector<int> owner(static_cast<std::size_t>(units), -1);
      long long smallest = units, largest = 0;
      for (int i = 0; i < n; ++i) {
        const vb::Shard s{i, n};
        long long mine = 0;
        for (long long u = 0; u < units; ++u) {
          if (!s.owns(u)) continue;
          EXPECT_EQ(owner[static_cast<std::size_t>(u)], -1) << "unit " << u << " in two shards";
          owner[static_cast<std::size_t>(u)] = i;
          ++mine;
        }
        EXPECT_EQ(s.owned(units), mine) << i << "/" << n << " of " << units;
        smallest = std::min(smallest, mine);
        largest = std::max(largest, mine);
      }
      for (int o : owner) EXPECT_GE(o, 0);
      EXPECT_LE(largest - smallest, 1) << n << " shards of " << units;
    }
  }
}

TEST(Shard, RowsSurviveTheJsonRoundTrip) {
  vb::TrialRecord r;
  r.solver = "clique";
  r.dataset = "synthetic";
  r.generator = "uniform";
  r.dim = 2;
  r.n = 77;
  r.outlier_ratio = 0.1 + 0.2;  // not exactly representable in decimal
  r.trial = 3;
  r.data_seed = 0xFFFFFFFFFFFFFFF1ull;
  r.solver_seed = 12345678901234ull;
  r.status = vb::Status::time_limit;
  r.accepted = true;
  r.inliers = 12;
  r.true_inliers = 11;
  r.inlier_precision = 11.0 / 12.0;
  r.success = false;
  r.time_ms = 1.25;
  r.branch_nodes = 1LL << 40;
  r.omega_upper_bound = 19;
  r.accept_rule = "pvalue";
  r.expected_positive = false;
  r.p_value = 1e-300;
  r.p_value_low = 1e-310;  // subnormal
  r.p_value_high = 0.004;
  r.null_threshold = 9;
  r.null_draws = 20;
  r.lever_arm = 3.5;
  r.prior_d2 = 31.25;
  r.runner_up = 10;
  r.runner_up_p = 2.5e-7;
  r.runner_up_separation = 41.5;
  r.runner_up_ambiguous = true;
  r.runner_up_rivals = 2;
  r.runner_up_support = 19;
  r.T_target_source = {1, 0, 0.5, 0, 1, -0.25, 0, 0, 1};
  const json j = vb::to_json(r);
  EXPECT_EQ(vb::to_json(vb::trial_from_json(json::parse(j.dump()))), j);
  EXPECT_EQ(j["runner_up_rivals"], 2);
  EXPECT_EQ(j["runner_up_support"], 19);
  EXPECT_TRUE(j["dense_check"].is_null());
  {  // The dense check's figures, an unconverged ICP's fitness (null) included.
    vb::TrialRecord d = r;
    d.dense_overlap = 0.1 + 0.2;
    d.dense_icp_converged = true;
    d.dense_icp_fitness = 0.0625;
    d.dense_ms = 12.5;
    d.dense_T_target_source = {1, 0, 0, 0.5, 0, 1, 0, -0.25, 0, 0, 1, 0, 0, 0, 0, 1};
    const json jd = vb::to_json(d);
    const vb::TrialRecord back = vb::trial_from_json(json::parse(jd.dump()));
    EXPECT_EQ(back.dense_overlap, d.dense_overlap);
    EXPECT_EQ(back.dense_T_target_source, d.dense_T_target_source);
    EXPECT_EQ(vb::to_json(back), jd);
    d.dense_icp_converged = false;
    d.dense_icp_fitness = vb::TrialRecord::kNaN;
    const json jn = vb::to_json(d);
    EXPECT_TRUE(jn["dense_check"]["icp_fitness_m2"].is_null());
    EXPECT_EQ(vb::to_json(vb::trial_from_json(json::parse(jn.dump()))), jn);
  }
  vb::CliqueRecord c;
  c.graph = "g.clq";
  c.algorithm = "bbmc";
  c.n = 5;
  c.edges = 7;
  c.status = vb::SearchStatus::ok;
  c.omega = 3;
  c.known_omega = 3;
  c.clique = {1, 2, 5};
  c.local_search_steps = 4;
  const json k = vb::to_json(c);
  EXPECT_EQ(vb::to_json(vb::clique_from_json(json::parse(k.dump()))), k);
  json broken = j;
  broken["inliers"] = "many";
  EXPECT_THROW(vb::trial_from_json(broken), std::invalid_argument);
  for (const json& range : {json(0.5), json::array({0.1}), json::array({0.1, "x"}),
                            json::array({0.1, 0.2, 0.3})}) {
    json bad_range = j;
    bad_range["p_value_range"] = range;
    try {
      vb::trial_from_json(bad_range);
      ADD_FAILURE() << "accepted p_value_range " << range.dump();
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("p_value_range"), std::string::npos) << e.what();
    }
  }
  // Every status name reads back as its enumerator; any other text is refused, naming it.
  for (vb::Status st : {vb::Status::ok, vb::Status::rejected, vb::Status::time_limit,
                        vb::Status::error}) {
    json row = j;
    row["status"] = vb::to_string(st);
    EXPECT_EQ(vb::trial_from_json(row).status, st);
  }
  for (vb::SearchStatus st : {vb::SearchStatus::ok, vb::SearchStatus::time_limit,
                              vb::SearchStatus::unproven, vb::SearchStatus::error}) {
    json row = k;
    row["status"] = vb::to_string(st);
    EXPECT_EQ(vb::clique_from_json(row).status, st);
  }
  json unknown = j;
  unknown["status"] = "unproven";  // a search status, not a solver's
  try {
    vb::trial_from_json(unknown);
    ADD_FAILURE() << "accepted status 'unproven' in a solver row";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("unknown status 'unproven'"), std::string::npos)
        << e.what();
  }
  json before = j;  // reports written before the range existed
  before.erase("p_value_range");
  EXPECT_TRUE(std::isnan(vb::trial_from_json(before).p_value_low));
}

TEST(ShardCli, MergedSweepEqualsTheUnshardedOne) {
  const fs::path dir = fresh_dir("vb_shard_sweep");
  const auto [whole, merged] = whole_and_merged(
      dir, "sweep --solvers clique,ransac --dim 2,3 --n 80 --outliers 0.5,0.9 --trials 4 --negatives", 3);
  EXPECT_EQ(whole["results"].size(), 2u * 2 * 4 * 2 * 2);
  expect_same_report(whole, merged);
  EXPECT_EQ(merged["context"]["shards"], 3);
  EXPECT_FALSE(merged["context"].contains("shard"));
}

TEST(ShardCli, ASlicesSetsDoNotDependOnTheNumberOfShards) {
  const fs::path dir = fresh_dir("vb_shard_n");
  const std::string sweep = "sweep --solvers clique --dim 3 --n 60 --outliers 0.6,0.8 --trials 5 --quiet";
  // Unit 4 (ratio 0.6, trial 4) is in shard 1/2 (4 % 2 = 0) and in shard 5/5 (4 % 5 = 4).
  ASSERT_EQ(run_cli(sweep + " --shard 1/2 --out " + (dir / "a.json").string()).code, 0);
  ASSERT_EQ(run_cli(sweep + " --shard 5/5 --out " + (dir / "b.json").string()).code, 0);
  auto find = [](const json& report) {
    for (const auto& row : report["results"]) {
      if (row["trial"] == 4 && row["outlier_ratio"] == 0.6) return row;
    }
    return json();
  };
  const json a = find(load(dir / "a.json")), b = find(load(dir / "b.json"));
  ASSERT_FALSE(a.is_null());
  ASSERT_FALSE(b.is_null());
  EXPECT_EQ(without_times(a), without_times(b));
  EXPECT_EQ(load(dir / "b.json")["results"].size(), 2u);  // units 4 and 9
}

TEST(ShardCli, MergedDumpRunAndDimacsRunEqualTheUnshardedOnes) {
  const fs::path dir = fresh_dir("vb_shard_run");
  vb::SyntheticParams p;
  p.n = 60;
  p.outlier_ratio = 0.7;
  const auto set = vb::make_synthetic<3>(p);
  fs::create_directories(dir / "dump");
  std::ofstream corr(dir / "dump" / "corr.txt"), label(dir / "dump" / "label.txt");
  for (Eigen::Index i = 0; i < set.corr.size(); ++i) {
    corr << set.corr.source.col(i).transpose() << " " << set.corr.target.col(i).transpose() << "\n";
    label << int(set.truth.labels[static_cast<std::size_t>(i)]) << "\n";
  }
  corr.close();
  label.close();
  const auto [whole, merged] = whole_and_merged(
      dir, "run --dump " + (dir / "dump").string() + " --solvers clique,ransac,lo-ransac --trials 3", 2);
  EXPECT_EQ(whole["results"].size(), 9u);
  expect_same_report(whole, merged);

  std::string graphs;
  std::mt19937_64 rng(3);
  for (int g = 0; g < 5; ++g) {
    const fs::path file = dir / ("g" + std::to_string(g) + ".clq");
    const vb::BitGraph graph = vb::test::random_graph(20 + 5 * g, 0.5, rng);
    std::ofstream out(file);
    out << "p edge " << graph.size() << " " << graph.edge_count() << "\n";
    for (int u = 0; u < graph.size(); ++u)
      for (int v = u + 1; v < graph.size(); ++v)
        if (graph.adjacent(u, v)) out << "e " << u + 1 << " " << v + 1 << "\n";
    graphs += " " + file.string();
  }
  const auto [dimacs_whole, dimacs_merged] =
      whole_and_merged(dir, "dimacs" + graphs + " --algorithms bbmc,greedy", 3);
  EXPECT_EQ(dimacs_whole["results"].size(), 10u);
  expect_same_report(dimacs_whole, dimacs_merged);
}

TEST(ShardCli, MergeRefusesShardsThatDoNotMakeOneRun) {
  const fs::path dir = fresh_dir("vb_shard_bad");
  const std::string sweep = "sweep --solvers clique --dim 3 --n 40 --outliers 0.5 --trials 3 --quiet";
  auto shard = [&](const std::string& extra, const std::string& name) {
    const auto r = run_cli(sweep + extra + " --out " + (dir / name).string());
    ASSERT_EQ(r.code, 0) << r.output;
  };
  shard(" --shard 1/2", "a1.json");
  shard(" --shard 2/2", "a2.json");
  shard(" --shard 2/2 --seed 9", "seed.json");
  shard(" --shard 2/3", "three.json");
  shard("", "plain.json");
  std::ofstream(dir / "broken.json") << "{\"schema_version\": 1, ";
  auto expect_refused = [&](const std::string& files, const std::string& needle) {
    const auto r = run_cli("merge " + files + " --out " + (dir / "m.json").string());
    EXPECT_EQ(r.code, 2) << files << "\n" << r.output;
    EXPECT_NE(r.output.find(needle), std::string::npos) << files << "\n" << r.output;
    EXPECT_FALSE(fs::exists(dir / "m.json"));
  };
  const std::string a1 = (dir / "a1.json").string(), a2 = (dir / "a2.json").string();
  expect_refused(a1, "shard 2/2 missing");
  expect_refused(a1 + " " + a1, "given twice");
  expect_refused(a1 + " " + (dir / "seed.json").string(), "command_line differs");
  expect_refused(a1 + " " + (dir / "three.json").string(), "count 3 differs");
  expect_refused((dir / "plain.json").string(), "not a shard's report");
  expect_refused((dir / "broken.json").string(), "broken.json: not JSON");
  expect_refused((dir / "absent.json").string(), "absent.json: not a regular file");
  const auto ok = run_cli("merge " + a2 + " " + a1 + " --out " + (dir / "m.json").string());
  EXPECT_EQ(ok.code, 0) << ok.output;
  EXPECT_EQ(load(dir / "m.json")["results"].size(), 3u);
}
