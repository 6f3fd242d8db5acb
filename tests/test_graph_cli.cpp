// `verifybench graph`: the DIMACS file is the Eq. (1) graph (checked against a brute-force
// evaluation here), `verifybench dimacs` on it finds the clique `run --solvers clique` finds on the
// dump, and bad input exits 2 naming the option or file.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "test_util.hpp"

namespace {

namespace fs = std::filesystem;
using verifybench::test::CliRun;
using verifybench::test::run_cli;

struct Point3 {
  double x, y, z;
};

double dist(const Point3& a, const Point3& b) {
  return std::sqrt((a.x - b.x) * (a.x - b.x) + (a.y - b.y) * (a.y - b.y) +
                   (a.z - b.z) * (a.z - b.z));
}

class GraphCli : public ::testing::Test {
 protected:
  static constexpr double kEps = 0.1;

  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("vb_graph_cli_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_ / "dump");
    // 24 inliers of one rigid motion (noise 0.02 m) and 16 uniform outliers in a 4 m cube;
    // written with 17 digits so that the CLI reads back exactly these doubles.
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> u(0.0, 4.0);
    std::normal_distribution<double> noise(0.0, 0.02);
    const double c = std::cos(0.4), s = std::sin(0.4);
    for (int i = 0; i < 40; ++i) {
      const Point3 m{u(rng), u(rng), u(rng)};
      Point3 q;
      if (i < 24) {
        q = {c * m.x - s * m.y + 1.0 + noise(rng), s * m.x + c * m.y - 0.5 + noise(rng),
             m.z + 0.3 + noise(rng)};
      } else {
        q = {u(rng), u(rng), u(rng)};
      }
      source_.push_back(m);
      target_.push_back(q);
    }
    std::ofstream f(dir_ / "dump" / "corr.txt");
    f.precision(17);
    for (std::size_t i = 0; i < source_.size(); ++i) {
      f << source_[i].x << ' ' << source_[i].y << ' ' << source_[i].z << ' ' << target_[i].x << ' '
        << target_[i].y << ' ' << target_[i].z << '\n';
    }
  }
  void TearDown() override { fs::remove_all(dir_); }

  /// Eq. (1) in double precision, every pair, 1-based.
  std::set<std::pair<int, int>> brute_force_edges(double eps) const {
    std::set<std::pair<int, int>> edges;
    const int n = static_cast<int>(source_.size());
    for (int i = 0; i < n; ++i) {
      for (int j = i + 1; j < n; ++j) {
        if (std::abs(dist(source_[i], source_[j]) - dist(target_[i], target_[j])) < eps)
          edges.insert({i + 1, j + 1});
      }
    }
    return edges;
  }

  std::string dump() const { return (dir_ / "dump").string(); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }

  fs::path dir_;
  std::vector<Point3> source_, target_;
};

struct Dimacs {
  int n = -1;
  long long m = -1;
  std::set<std::pair<int, int>> edges;
  std::vector<std::string> comments;
  long long edge_lines = 0;
};

Dimacs parse_dimacs(std::istream& in) {
  Dimacs d;
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream ls(line);
    std::string tag;
    ls >> tag;
    if (tag == "c") {
      d.comments.push_back(line);
    } else if (tag == "p") {
      std::string kind;
      ls >> kind >> d.n >> d.m;
      EXPECT_EQ(kind, "edge");
    } else if (tag == "e") {
      int u = 0, v = 0;
      ls >> u >> v;
      EXPECT_LT(u, v) << line;  // each edge once, u < v
      EXPECT_GE(u, 1) << line;
      EXPECT_LE(v, d.n) << line;
      d.edges.insert({u, v});
      ++d.edge_lines;
    } else {
      ADD_FAILURE() << "unexpected line: " << line;
    }
  }
  return d;
}

bool has_comment(const Dimacs& d, const std::string& text) {
  for (const auto& c : d.comments)
    if (c == text) return true;
  return false;
}

TEST_F(GraphCli, WritesExactlyTheEquationOneGraph) {
  for (double eps : {kEps, 0.05, 0.5}) {
    const std::string out = path("g_" + std::to_string(eps) + ".clq");
    std::ostringstream args;
    args.precision(17);
    args << "graph --dump " << dump() << " --eps " << eps << " --out " << out << " --quiet";
    const CliRun r = run_cli(args.str());
    ASSERT_EQ(r.code, 0) << r.output;
    EXPECT_EQ(r.output, out + "\n");
    std::ifstream f(out);
    const Dimacs d = parse_dimacs(f);
    const auto expected = brute_force_edges(eps);
    EXPECT_EQ(d.n, 40);
    EXPECT_EQ(d.m, static_cast<long long>(expected.size()));
    EXPECT_EQ(d.edge_lines, d.m);  // no duplicates
    EXPECT_EQ(d.edges, expected) << "eps " << eps;
    EXPECT_TRUE(has_comment(d, "c dump " + dump()));
    EXPECT_TRUE(has_comment(d, "c n 40"));
    EXPECT_TRUE(has_comment(d, "c m " + std::to_string(expected.size())));
    EXPECT_TRUE(has_comment(d, "c dim 3"));
    EXPECT_FALSE(expected.empty());
    EXPECT_LT(expected.size(), 40u * 39u / 2u);
    // No temporary left beside it.
    for (const auto& e : fs::directory_iterator(dir_))
      EXPECT_EQ(e.path().string().find(".tmp."), std::string::npos) << e.path();
  }
  const CliRun r = run_cli("graph --dump " + dump() + " --eps 0.1 --out " + path("h.clq") + " --quiet");
  ASSERT_EQ(r.code, 0) << r.output;
  std::ifstream f(path("h.clq"));
  EXPECT_TRUE(has_comment(parse_dimacs(f), "c eps 0.1"));
}

TEST_F(GraphCli, DimacsOmegaEqualsTheCliqueSolversInliers) {
  const std::string g = path("g.clq"), dj = path("dimacs.json"), rj = path("run.json");
  ASSERT_EQ(run_cli("graph --dump " + dump() + " --eps 0.1 --out " + g + " --quiet").code, 0);
  const CliRun d = run_cli("dimacs " + g + " --quiet --out " + dj);
  ASSERT_EQ(d.code, 0) << d.output;
  const CliRun r = run_cli("run --dump " + dump() +
                           " --eps 0.1 --solvers clique --accept count --quiet --out " + rj);
  ASSERT_EQ(r.code, 0) << r.output;
  const auto dimacs = nlohmann::json::parse(std::ifstream(dj));
  const auto run = nlohmann::json::parse(std::ifstream(rj));
  ASSERT_EQ(dimacs["results"].size(), 1u);
  ASSERT_EQ(run["results"].size(), 1u);
  const auto& dr = dimacs["results"][0];
  const auto& rr = run["results"][0];
  EXPECT_EQ(dr["status"], "ok");
  EXPECT_EQ(rr["status"], "ok");
  EXPECT_EQ(dr["omega"].get<int>(), rr["inliers"].get<int>());
  EXPECT_EQ(dr["edges"].get<long long>(), rr["graph_edges"].get<long long>());
  EXPECT_GE(dr["omega"].get<int>(), 20) << dr.dump();  // the 24 inliers, bar a noisy one or two
}

TEST_F(GraphCli, StdoutAndOverwrite) {
  const std::string g = path("g.clq");
  ASSERT_EQ(run_cli("graph --dump " + dump() + " --out " + g + " --quiet").code, 0);
  const CliRun s = run_cli("graph --dump " + dump() + " --out - --quiet");
  ASSERT_EQ(s.code, 0) << s.output;
  std::ifstream f(g);
  std::stringstream file;
  file << f.rdbuf();
  EXPECT_EQ(s.output, file.str());  // the default eps is run's, 0.1
  const CliRun o = run_cli("graph --dump " + dump() + " --eps 0.5 --out " + g + " --overwrite --quiet");
  ASSERT_EQ(o.code, 0) << o.output;
  std::ifstream f2(g);
  EXPECT_EQ(parse_dimacs(f2).edges, brute_force_edges(0.5));
}

TEST_F(GraphCli, BadInputExitsTwoNamingTheOptionOrFile) {
  auto expect_error = [](const std::string& args, const std::string& needle) {
    const CliRun r = run_cli(args);
    EXPECT_EQ(r.code, 2) << args << "\n" << r.output;
    EXPECT_NE(r.output.find("verifybench: error:"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find(needle), std::string::npos) << args << "\n" << r.output;
  };
  const std::string g = path("g.clq");
  const std::string missing = path("no_such_dump");
  expect_error("graph --dump " + missing + " --out " + g, missing);
  expect_error("graph --dump " + dump() + " --eps 0 --out " + g, "--eps");
  expect_error("graph --dump " + dump() + " --eps -0.1 --out " + g, "--eps");
  expect_error("graph --dump " + dump() + " --eps nan --out " + g, "--eps");
  expect_error("graph --out " + g, "--dump is required");
  expect_error("graph --dump " + dump(), "--out is required");
  expect_error("graph --dump " + dump() + " --out " + path("no_dir/g.clq"), "no_dir");
  ASSERT_EQ(run_cli("graph --dump " + dump() + " --out " + g + " --quiet").code, 0);
  { std::ofstream(g) << "keep me\n"; }
  expect_error("graph --dump " + dump() + " --out " + g, g);
  std::ifstream f(g);
  std::string kept;
  std::getline(f, kept);
  EXPECT_EQ(kept, "keep me");  // the refused file is untouched
  // A malformed dump names its file.
  { std::ofstream(dir_ / "dump" / "corr.txt", std::ios::app) << "1 2 3 4 5\n"; }
  expect_error("graph --dump " + dump() + " --out " + path("bad.clq"), "corr.txt");
}

}  // namespace
