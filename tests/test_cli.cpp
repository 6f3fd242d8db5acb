// The CLI: bad input gives one clear line on stderr and exit code 2; good input writes a report.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "test_util.hpp"

namespace {

namespace fs = std::filesystem;

using verifybench::test::CliRun;
CliRun run(const std::string& args) { return verifybench::test::run_cli(args); }

void expect_usage_error(const std::string& args, const std::string& needle) {
  const CliRun r = run(args);
  EXPECT_EQ(r.code, 2) << args << "\n" << r.output;
  EXPECT_NE(r.output.find("verifybench: error:"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find(needle), std::string::npos) << args << "\n" << r.output;
}

const std::string kOut = "--out " + (fs::temp_directory_path() / "vb_cli.json").string();

TEST(Cli, RejectsBadInputWithExitCode2) {
  expect_usage_error("frobnicate", "unknown command 'frobnicate'");
  expect_usage_error("sweep --bogus 1 " + kOut, "unknown option '--bogus'");
  expect_usage_error("sweep --solvers clique,nope " + kOut, "unknown solver 'nope'");
  expect_usage_error("sweep --solvers clique, " + kOut, "--solvers: 'clique,' has an empty item");
  expect_usage_error("sweep --quiet=1 " + kOut, "option --quiet takes no value");
  expect_usage_error("sweep --n 5 --n 6 " + kOut, "option --n given twice");
  expect_usage_error("sweep stray " + kOut, "unexpected argument 'stray'");
  expect_usage_error("sweep --n -5 " + kOut, "--n: '-5' is outside");
  expect_usage_error("sweep --n abc " + kOut, "--n: 'abc' is not an integer");
  expect_usage_error("sweep --outliers 0.5:1.5:0.1 " + kOut, "1.5 is outside [0, 1]");
  expect_usage_error("sweep --outliers 0.9:0.5:0.1 " + kOut, "below start");
  expect_usage_error("sweep --outliers 0.1:0.5:0 " + kOut, "must be > 0");
  expect_usage_error("sweep --eps nan " + kOut, "--eps: 'nan' is not a finite number");
  expect_usage_error("sweep --dim 4 " + kOut, "--dim: '4' is not 2 or 3");
  expect_usage_error("sweep --trials", "--trials needs a value");
  expect_usage_error("sweep --n 10", "--out is required");
  expect_usage_error("run --dump /nonexistent/dir " + kOut, "/nonexistent/dir");
  expect_usage_error("run " + kOut, "--dump is required");
  expect_usage_error("", "usage:");
  expect_usage_error("sweep --generator blobs " + kOut, "unknown kind 'blobs' (known: uniform");
  expect_usage_error("sweep --generator bev-orb --dim 2,3 " + kOut, "bev-orb does not exist in 3D");
  expect_usage_error("sweep --prior-rot-deg 2 " + kOut, "--prior-rot-deg and --prior-trans");
  expect_usage_error("sweep --accept vote " + kOut, "accept rule 'vote' is unknown");
  expect_usage_error("sweep --alpha 0 " + kOut, "--alpha: '0' is outside");
  expect_usage_error("sweep --null-draws 1 " + kOut, "--null-draws: '1' is outside");
  expect_usage_error("sweep --max-null-draws -1 " + kOut, "--max-null-draws: '-1' is outside");
  expect_usage_error("sweep --prior-gate 1 " + kOut, "--prior-gate: '1' is outside");
  expect_usage_error("run --dump x --expected maybe " + kOut, "--expected: 'maybe'");
  expect_usage_error("sweep --overlap 0 " + kOut, "--overlap: '0' is outside");
  expect_usage_error("sweep --jcbb-confidence 1 " + kOut, "--jcbb-confidence");
  if (VB_BUILT_FRONTEND) {
    expect_usage_error(
        "extract --source /nonexistent/a.bin --target /nonexistent/b.bin --out /tmp/x",
        "/nonexistent/a.bin: no such file");
    expect_usage_error("extract --pipeline 4d --source a --target b --out /tmp/x",
                       "is not 3d or 2d");
    expect_usage_error("extract --source a.bin --out /tmp/x", "--target is required");
    expect_usage_error("extract --matching closest --source a --target b --out /tmp/x",
                       "--matching: matching policy 'closest' is not nearest, mutual");
  } else {
    expect_usage_error("extract --source a.bin --out /tmp/x", "this build has no front end");
  }
}

// Each solver family's options are declared once (ParamField rows): a value given on the command
// line reaches the report under the field's key, and a value out of range names the option.
TEST(Cli, FamilyOptionsReachTheReportAndAreRangeChecked) {
  const fs::path out = fs::temp_directory_path() / "vb_cli_family.json";
  fs::remove(out);
  const CliRun r =
      run("sweep --n 30 --outliers 0.5 --trials 1 --solvers ransac,mac,jcbb --ransac-iterations 77 "
          "--ransac-adaptive --ransac-confidence 0.9 --mac-max-cliques 12345 --mac-min-clique 4 "
          "--jcbb-sigma 0.02 --jcbb-confidence 0.9 --quiet --out " +
          out.string());
  ASSERT_EQ(r.code, 0) << r.output;
  std::ifstream in(out);
  const auto p = nlohmann::json::parse(in)["parameters"];
  EXPECT_EQ(p["ransac_iterations"], 77);
  EXPECT_EQ(p["ransac_adaptive"], true);
  EXPECT_DOUBLE_EQ(p["ransac_confidence"].get<double>(), 0.9);
  EXPECT_EQ(p["mac_max_cliques"], 12345);
  EXPECT_EQ(p["mac_min_clique"], 4);
  EXPECT_DOUBLE_EQ(p["jcbb_sigma"].get<double>(), 0.02);
  EXPECT_DOUBLE_EQ(p["jcbb_confidence"].get<double>(), 0.9);
  fs::remove(out);
  expect_usage_error("sweep --ransac-iterations 0 " + kOut, "--ransac-iterations: '0' is outside");
  expect_usage_error("sweep --mac-min-clique 1 " + kOut, "--mac-min-clique: '1' is outside");
  expect_usage_error("sweep --ransac-confidence 1.5 " + kOut, "--ransac-confidence: '1.5'");
  const CliRun help = run("sweep --help");
  EXPECT_NE(help.output.find("--ransac-iterations K"), std::string::npos) << help.output;
  EXPECT_NE(help.output.find("(default 10000)"), std::string::npos) << help.output;
  const CliRun version = run("--version");
  EXPECT_EQ(version.code, 0);
  EXPECT_EQ(version.output.rfind("verifybench ", 0), 0u) << version.output;
}

TEST(Cli, MalformedDumpNamesFileAndLine) {
  const fs::path dir = fs::temp_directory_path() / "vb_cli_dump";
  fs::create_directories(dir);
  std::ofstream(dir / "corr.txt") << "0 0 0 1 1 1\n0 0 0 1 1 oops\n";
  expect_usage_error("run --dump " + dir.string() + " " + kOut, "corr.txt:2: field column 6");
  std::ofstream(dir / "corr.txt") << "0 0 0 1 1 1\n0 1 0 1 2 1\n";  // valid, but no GTmat.txt
  expect_usage_error("run --prior-rot-deg 1 --prior-trans 0.1 --dump " + dir.string() + " " + kOut,
                     "has no ground truth to draw a prior around");
  fs::remove_all(dir);
}

TEST(Cli, ListAndHelp) {
  const CliRun list = run("list");
  EXPECT_EQ(list.code, 0);
  for (const char* name :
       {"clique", "ransac", "lo-ransac", "jcbb", "generators", "rigid-group", "bev-orb"}) {
    EXPECT_NE(list.output.find(name), std::string::npos) << name;
  }
  EXPECT_EQ(list.output.find("pcl-ransac") != std::string::npos, bool(VB_BUILT_PCL));
  EXPECT_EQ(list.output.find("open3d-ransac") != std::string::npos, bool(VB_BUILT_OPEN3D));
  for (const char* cmd : {"sweep --help", "run --help", "list --help", "--help"}) {
    const CliRun r = run(cmd);
    EXPECT_EQ(r.code, 0) << cmd;
    EXPECT_NE(r.output.find("usage"), std::string::npos) << cmd;
  }
}

TEST(Cli, SweepWithNegativesScoresEveryDecision) {
  // Each trial draws a positive and its negative twin: per solver, TP + FN and FP + TN both equal
  // the number of (dim, ratio, trial) points, under either rule.
  const fs::path out = fs::temp_directory_path() / "vb_cli_negatives.json";
  for (const std::string rule : {"pvalue", "count"}) {
    fs::remove(out);
    const CliRun r = run("sweep --dim 2,3 --n 80 --outliers 0.5 --trials 3 --negatives --accept " +
                         rule + " --quiet --out " + out.string());
    ASSERT_EQ(r.code, 0) << r.output;
    std::ifstream in(out);
    const auto doc = nlohmann::json::parse(in);
    EXPECT_EQ(doc["parameters"]["accept_rule"], rule);
    ASSERT_EQ(doc["decisions"].size(), 2u);  // clique, ransac
    for (const auto& d : doc["decisions"]) {
      EXPECT_EQ(d["tp"].get<int>() + d["fn"].get<int>(), 6) << d;
      EXPECT_EQ(d["fp"].get<int>() + d["tn"].get<int>(), 6) << d;
    }
    int negatives = 0;
    for (const auto& row : doc["results"]) {
      EXPECT_EQ(row["accept_rule"], rule);
      if (row["expected"] == "negative") {
        ++negatives;
        EXPECT_TRUE(row["success"].is_null());
        EXPECT_EQ(row["decision"], row["accepted"].get<bool>() ? "FP" : "TN");
      }
      EXPECT_EQ(row["p_value"].is_null(), rule == "count");
      if (rule == "count") {
        EXPECT_TRUE(row["p_value_range"].is_null());
      } else {
        ASSERT_EQ(row["p_value_range"].size(), 2u);
        EXPECT_LE(row["p_value_range"][0].get<double>(), row["p_value"].get<double>());
        EXPECT_LE(row["p_value"].get<double>(), row["p_value_range"][1].get<double>());
      }
    }
    EXPECT_EQ(negatives, 12);
  }
  fs::remove(out);
}

TEST(Cli, SweepWritesAParsableReport) {
  const fs::path out = fs::temp_directory_path() / "vb_cli_sweep.json";
  fs::remove(out);
  const CliRun r =
      run("sweep --dim 2,3 --n 60 --outliers 0.5,0.8 --trials 2 --seed 9 --quiet --out " +
          out.string());
  ASSERT_EQ(r.code, 0) << r.output;
  std::ifstream in(out);
  const auto doc = nlohmann::json::parse(in);
  EXPECT_EQ(doc["context"]["seed"], 9);
  EXPECT_EQ(doc["results"].size(), 2u * 2u * 2u * 2u);  // dims x ratios x trials x solvers
  EXPECT_EQ(doc["aggregates"].size(), 2u * 2u * 2u);
  fs::remove(out);
}

TEST(Cli, DimacsModeReportsOmegaAndRejectsBadInput) {
  const fs::path dir = fs::temp_directory_path() / "vb_cli_dimacs";
  fs::create_directories(dir);
  // K4 on {1,2,3,4} plus a pendant vertex 5; MANIFEST.tsv gives the known omega.
  std::ofstream(dir / "k4.clq") << "p edge 5 7\ne 1 2\ne 1 3\ne 1 4\ne 2 3\ne 2 4\ne 3 4\ne 4 5\n";
  std::ofstream(dir / "MANIFEST.tsv") << "instance\tn\tm\tomega\nk4\t5\t7\t4\n";
  std::ofstream(dir / "bad.clq") << "p edge 5 1\ne 1 9\n";
  const fs::path out = dir / "r.json";
  const std::string algorithms = std::string("bbmc") + (VB_BUILT_CLIQUER ? ",cliquer" : "") +
                                 (VB_BUILT_IGRAPH ? ",igraph" : "");
  const CliRun ok = run("dimacs " + (dir / "k4.clq").string() + " --algorithms " + algorithms +
                        " --quiet --out " + out.string());
  ASSERT_EQ(ok.code, 0) << ok.output;
  std::ifstream in(out);
  const auto doc = nlohmann::json::parse(in);
  ASSERT_EQ(doc["results"].size(), 1u + VB_BUILT_CLIQUER + VB_BUILT_IGRAPH);
  for (const auto& r : doc["results"]) {
    EXPECT_EQ(r["omega"], 4) << r["algorithm"];
    EXPECT_EQ(r["status"], "ok");
    EXPECT_EQ(r["correct"], true);
    EXPECT_EQ(r["clique"], (std::vector<int>{1, 2, 3, 4}));
  }
  for (const auto& a : doc["aggregates"]) {
    EXPECT_EQ(a["proven"], 1);
    EXPECT_EQ(a["correct"], 1);
    EXPECT_EQ(a["found_unproved"], 0);
  }
  // On a 5-cycle (omega 2, every core number 2: bound 3) a heuristic finds a maximum clique but
  // proves nothing: not "correct", counted as found.
  std::ofstream(dir / "c5.clq") << "p edge 5 5\ne 1 2\ne 2 3\ne 3 4\ne 4 5\ne 5 1\n";
  std::ofstream(dir / "MANIFEST.tsv", std::ios::app) << "c5\t5\t5\t2\n";
  const CliRun greedy = run("dimacs " + (dir / "c5.clq").string() +
                            " --algorithms greedy --quiet --out " + (dir / "g.json").string());
  ASSERT_EQ(greedy.code, 0) << greedy.output;
  std::ifstream gin(dir / "g.json");
  const auto gdoc = nlohmann::json::parse(gin);
  ASSERT_EQ(gdoc["results"].size(), 1u);
  EXPECT_EQ(gdoc["results"][0]["omega"], 2);
  EXPECT_EQ(gdoc["results"][0]["known_omega"], 2);
  EXPECT_NE(gdoc["results"][0]["status"], "ok");
  EXPECT_TRUE(gdoc["results"][0]["correct"].is_null()) << gdoc["results"][0].dump();
  EXPECT_EQ(gdoc["aggregates"][0]["proven"], 0);
  EXPECT_EQ(gdoc["aggregates"][0]["correct"], 0);
  EXPECT_EQ(gdoc["aggregates"][0]["found_unproved"], 1);
  EXPECT_EQ(gdoc["aggregates"][0]["wrong"], 0);
  expect_usage_error("dimacs " + (dir / "bad.clq").string() + " " + kOut, "bad.clq:2: vertex '9'");
  expect_usage_error("dimacs " + (dir / "k4.clq").string() + " --algorithms nope " + kOut,
                     "unknown clique algorithm 'nope'");
  expect_usage_error("dimacs " + kOut, "no DIMACS file given");
  fs::remove_all(dir);
}

TEST(Cli, GraphBeyondTheMemoryCapIsAnErrorNotACrash) {
  const fs::path out = fs::temp_directory_path() / "vb_cli_cap.json";
  const CliRun r =
      run("sweep --n 20000 --outliers 0.5 --trials 1 --max-graph-mb 10 --solvers clique --quiet "
          "--out " +
          out.string());
  EXPECT_EQ(r.code, 1) << r.output;
  EXPECT_NE(r.output.find("20000 vertices needs 47 MiB of adjacency rows, over the cap of 10 MiB"),
            std::string::npos)
      << r.output;
  std::ifstream in(out);
  const auto doc = nlohmann::json::parse(in);  // the report is complete and says why
  EXPECT_EQ(doc["results"][0]["status"], "error");
  fs::remove(out);
}

TEST(Cli, ReportIntoMissingFolderFailsCleanly) {
  const CliRun r =
      run("sweep --n 20 --outliers 0.5 --trials 1 --quiet --out /nonexistent/dir/r.json");
  EXPECT_EQ(r.code, 2);  // found before the work, not after it
  EXPECT_NE(r.output.find("--out: cannot write report /nonexistent/dir/r.json"), std::string::npos)
      << r.output;
  EXPECT_EQ(r.output.find("sweep"), std::string::npos)
      << "no progress before the refusal: " << r.output;
  for (const std::string cmd : {"sweep --n 20 --trials 1 --quiet", "dimacs x.clq --quiet"}) {
    const CliRun d = run(cmd + " --out /dev/null");
    EXPECT_EQ(d.code, 2) << cmd << "\n" << d.output;
    EXPECT_NE(d.output.find("it is a device"), std::string::npos) << d.output;
  }
}

}  // namespace

TEST(Cli, StructuredSweepWithPriorsRecordsGeneratorAndShape) {
  const fs::path out = fs::temp_directory_path() / "vb_cli_structured.json";
  fs::remove(out);
  const CliRun r =
      run("sweep --generator rigid-group --group-ratio 0.4 --solvers jcbb,lo-ransac --n 80 "
          "--outliers 0.5 --trials 2 --prior-rot-deg 1 --prior-trans 0.2 --quiet --out " +
          out.string());
  ASSERT_EQ(r.code, 0) << r.output;
  std::ifstream in(out);
  const auto doc = nlohmann::json::parse(in);
  EXPECT_EQ(doc["parameters"]["sweep"]["generator"], "rigid-group");
  EXPECT_EQ(doc["parameters"]["sweep"]["generator_shape"]["group_ratio"], 0.4);
  EXPECT_EQ(doc["parameters"]["sweep"]["prior_sigma_trans"], 0.2);
  ASSERT_EQ(doc["results"].size(), 4u);
  for (const auto& row : doc["results"]) EXPECT_EQ(row["generator"], "rigid-group");
  for (const auto& agg : doc["aggregates"]) EXPECT_EQ(agg["generator"], "rigid-group");
  fs::remove(out);
}

namespace {

// A 3D text dump of `n` correspondences on a known motion (a shift of (1, 2, 3)), labels given.
fs::path labelled_dump(const std::string& name, bool any_true) {
  const fs::path dir = fs::temp_directory_path() / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::ofstream corr(dir / "corr.txt"), label(dir / "label.txt");
  for (int i = 0; i < 30; ++i) {
    const double x = i % 5, y = (i / 5) % 3, z = i * 0.37;
    corr << x << " " << y << " " << z << " " << x + 1 << " " << y + 2 << " " << z + 3 << "\n";
    label << (any_true && i < 20 ? 1 : 0) << "\n";
  }
  return dir;
}

/// The CLI's stdout alone (stderr dropped) and its exit code.
CliRun stdout_of(const std::string& args) {
  const std::string cmd = std::string(VERIFYBENCH_CLI) + " " + args + " 2>/dev/null";
  FILE* pipe = popen(cmd.c_str(), "r");
  std::string text;
  char buf[4096];
  while (pipe && fgets(buf, sizeof buf, pipe)) text += buf;
  const int status = pipe ? pclose(pipe) : -1;
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, text};
}

}  // namespace

TEST(Cli, UnknownNamesSuggestTheNearestKnownOne) {
  expect_usage_error("sweep --solver clique " + kOut, "did you mean --solvers?");
  expect_usage_error("sweep --outlier 0.5 " + kOut, "did you mean --outliers?");
  expect_usage_error("sweep --solvers clqiue " + kOut, "did you mean 'clique'?");
  expect_usage_error("sweep --solvers sc2 " + kOut, "did you mean 'sc2-pcr'?");
  expect_usage_error("sweep --generator unifrom " + kOut, "did you mean 'uniform'?");
  // Nothing near: no suggestion, the list of known names only.
  const CliRun far = run("sweep --solvers zzzzzzzz " + kOut);
  EXPECT_EQ(far.code, 2);
  EXPECT_EQ(far.output.find("did you mean"), std::string::npos) << far.output;
  EXPECT_NE(far.output.find("known: "), std::string::npos) << far.output;
}

TEST(Cli, ShortAliasesAndTheReportOnStdout) {
  const fs::path out = fs::temp_directory_path() / "vb_cli_alias.json";
  fs::remove(out);
  const CliRun r = run("sweep --n 30 --outliers 0.5 --trials 1 -q -o " + out.string());
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_TRUE(fs::exists(out));
  EXPECT_EQ(r.output, out.string() + "\n");  // -q: only the path
  // --out -: the report itself on stdout (stderr left out here), no file named '-'.
  const CliRun piped = stdout_of("sweep --n 30 --outliers 0.5 --trials 1 --quiet --out -");
  ASSERT_EQ(piped.code, 0);
  const auto doc = nlohmann::json::parse(piped.output);
  EXPECT_EQ(doc["schema_version"], 1);
  EXPECT_EQ(doc["results"].size(), 2u);  // clique and ransac, one set
  EXPECT_FALSE(fs::exists("-"));
  EXPECT_NE(run("sweep --help").output.find("-o, --out FILE.json"), std::string::npos);
}

TEST(Cli, ExpectedDecisionFollowsTheLabels) {
  for (const bool any_true : {true, false}) {
    const fs::path dir =
        labelled_dump(any_true ? "vb_cli_labels_pos" : "vb_cli_labels_neg", any_true);
    const fs::path out = dir / "r.json";
    const CliRun r = run("run --dump " + dir.string() +
                         " --solvers clique --eps 0.05 --accept count "
                         "--quiet --out " +
                         out.string());
    ASSERT_EQ(r.code, 0) << r.output;
    std::ifstream in(out);
    const auto doc = nlohmann::json::parse(in);
    EXPECT_EQ(doc["results"][0]["expected"], any_true ? "positive" : "negative");
    // Given, it wins over the labels.
    const CliRun given = stdout_of("run --dump " + dir.string() +
                                   " --solvers clique --eps 0.05 "
                                   "--accept count --expected negative --quiet --out -");
    ASSERT_EQ(given.code, 0);
    EXPECT_EQ(nlohmann::json::parse(given.output)["results"][0]["expected"], "negative");
  }
}

TEST(Cli, DumpGivenAsItsFileNamesTheFolderToPass) {
  const fs::path dir = labelled_dump("vb_cli_dumpfile", true);
  expect_usage_error("run --dump " + (dir / "corr.txt").string() + " " + kOut,
                     "--dump takes the dump's folder (" + dir.string() + ")");
}
