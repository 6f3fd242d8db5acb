// Solvers through the registry: recovery of drawn motions, reproducibility, status and errors.
#include <gtest/gtest.h>

#include <limits>
#include <tuple>

#include "acceptance/verify.hpp"
#include "cliques/max_clique.hpp"
#include "core/metrics.hpp"
#include "core/timer.hpp"
#include "generators/synthetic.hpp"
#include "graph/compatibility_graph.hpp"
#include "harness/builtin.hpp"
#include "solvers/registry.hpp"

namespace verifybench {
namespace {

class Registered : public ::testing::Test {
 protected:
  void SetUp() override { register_builtin_solvers(); }
};

TEST_F(Registered, ListsBuiltinsAndRefusesUnknownNames) {
  std::vector<std::string> names;
  for (const auto& info : SolverRegistry::list()) {
    names.push_back(info.name);
    EXPECT_FALSE(info.description.empty());
  }
  // clique (the default algorithm), one clique-<algorithm> per registered algorithm, ransac.
  std::vector<std::string> expected{"clique",    "clipper",   "fastmac", "gnc-tls",
                                    "jcbb",      "lo-ransac", "mac",     "msac",
                                    "prosac",    "quatro",    "ransac",  "ransac-adaptive",
                                    "robin-gnc", "sc2-pcr",   "teaser",  "turboreg"};
  if (VB_BUILT_OPEN3D) expected.insert(expected.end(), {"open3d-ransac", "open3d-ransac-default"});
  if (VB_BUILT_PCL) {
    expected.insert(expected.end(), {"pcl-prerejective", "pcl-prerejective-default", "pcl-ransac",
                                     "pcl-ransac-default"});
  }
  for (const auto& algo : CliqueAlgorithms::list()) expected.push_back("clique-" + algo.name);
  std::sort(expected.begin(), expected.end());
  EXPECT_EQ(names, expected);
  EXPECT_TRUE(SolverRegistry::contains("clique-bbmc"));
  EXPECT_EQ(SolverRegistry::contains("clique-cliquer"), bool(VB_BUILT_CLIQUER));
  try {
    SolverRegistry::create("ransack");
    FAIL();
  } catch (const UnknownSolver& e) {
    EXPECT_NE(std::string(e.what()).find("ransack"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("clique, clique-auto, clique-bbmc"), std::string::npos)
        << e.what();
  }
  EXPECT_THROW(SolverRegistry::add({"clique", "again", nullptr}), std::logic_error);
}

// Every solver x dimension recovers a drawn motion at 50% outliers.
using Case = std::tuple<std::string, int>;
class Recovers : public ::testing::TestWithParam<Case> {
 protected:
  void SetUp() override { register_builtin_solvers(); }
};

template <int Dim>
void expect_recovery(const std::string& name) {
  const auto solver = SolverRegistry::create(name);
  for (std::uint64_t seed = 1; seed <= 5; ++seed) {
    SyntheticParams p;
    p.n = 200;
    p.outlier_ratio = 0.5;
    p.seed = seed;
    p.planar_motion = name == "quatro";  // quasi-SO(3): defined for yaw-only motions
    const auto set = make_synthetic<Dim>(p);
    SolverParams sp;
    sp.seed = seed;
    const Result<Dim> r = solver->solve(set.corr, sp);
    ASSERT_EQ(r.status, Status::ok) << r.message;
    EXPECT_TRUE(r.accepted);
    EXPECT_LT(rotation_error_deg(r.T_target_source, *set.truth.T_target_source), 0.5);
    EXPECT_LT(translation_error(r.T_target_source, *set.truth.T_target_source), 0.05);
    const auto s = inlier_scores(r.inliers, set.truth.labels);
    EXPECT_GT(s.precision, 0.95);
    EXPECT_GT(s.recall, 0.95);
  }
}

// The peers' "-default" entries run the libraries' own defaults (Open3D's 100,000 iterations with
// no checker, PCL's prerejective similarity 0.6), kept to show what a user gets out of the box;
// they need not recover here, but must answer without an error.
template <int Dim>
void expect_an_answer(const std::string& name) {
  SyntheticParams p;
  p.n = 200;
  p.outlier_ratio = 0.5;
  const auto set = make_synthetic<Dim>(p);
  const Result<Dim> r = SolverRegistry::create(name)->solve(set.corr, SolverParams{});
  EXPECT_NE(r.status, Status::error) << r.message;
}

TEST_P(Recovers, DrawnMotionAtHalfOutliers) {
  const auto& [name, dim] = GetParam();
  if (name.size() > 8 && name.compare(name.size() - 8, 8, "-default") == 0) {
    if (dim == 2) {
      expect_an_answer<2>(name);
    } else {
      expect_an_answer<3>(name);
    }
    return;
  }
  if (dim == 2)
    expect_recovery<2>(name);
  else
    expect_recovery<3>(name);
}

// Every registered solver, the peers included: a new solver is in this suite from the day it is
// registered.
std::vector<std::string> registered_names() {
  register_builtin_solvers();
  std::vector<std::string> names;
  for (const auto& info : SolverRegistry::list()) names.push_back(info.name);
  return names;
}

INSTANTIATE_TEST_SUITE_P(AllSolvers, Recovers,
                         ::testing::Combine(::testing::ValuesIn(registered_names()),
                                            ::testing::Values(2, 3)),
                         [](const auto& info) {
                           std::string name = std::get<0>(info.param);
                           for (char& c : name) {
                             if (c == '-') c = '_';
                           }
                           return name + "_" + std::to_string(std::get<1>(info.param)) + "D";
                         });

TEST_F(Registered, RansacIsReproducibleForASeed) {
  SyntheticParams p;
  p.n = 300;
  p.outlier_ratio = 0.9;
  const auto set = make_synthetic<3>(p);
  const auto ransac = SolverRegistry::create("ransac");
  SolverParams sp;
  sp.ransac.iterations = 2000;
  sp.seed = 77;
  const auto a = ransac->solve(set.corr, sp);
  const auto b = ransac->solve(set.corr, sp);
  EXPECT_EQ(a.inliers, b.inliers);
  EXPECT_TRUE(a.T_target_source.matrix() == b.T_target_source.matrix());
  EXPECT_EQ(a.counters.iterations, 2000);
  EXPECT_EQ(b.counters.iterations, 2000);
}

TEST_F(Registered, RansacAdaptiveStopsEarlyOnCleanData) {
  SyntheticParams p;
  p.n = 100;
  p.outlier_ratio = 0.0;
  const auto set = make_synthetic<3>(p);
  SolverParams sp;
  sp.ransac.adaptive = true;
  const auto r = SolverRegistry::create("ransac")->solve(set.corr, sp);
  // All 100 inliers are found by the first good sample, so k = log(0.001)/log(1 - 1) -> 0.
  EXPECT_LT(r.counters.iterations, 10);
  EXPECT_EQ(r.inliers.size(), 100u);
}

TEST_F(Registered, TooFewInliersAreRejected) {
  SyntheticParams p;
  p.n = 100;
  p.outlier_ratio = 0.97;  // 3 inliers, under the 5 that 3D acceptance needs
  const auto set = make_synthetic<3>(p);
  for (const char* name : {"clique", "ransac", "mac"}) {
    const auto r = SolverRegistry::create(name)->solve(set.corr, SolverParams{});
    EXPECT_FALSE(r.accepted) << name;
    EXPECT_EQ(r.status, Status::rejected) << name;
  }
}

TEST_F(Registered, BadInputBecomesAnErrorStatusNotACrash) {
  Correspondences<3> c;
  c.source = Eigen::Matrix3Xd::Random(3, 10);
  c.target = c.source;
  c.target(1, 4) = std::numeric_limits<double>::quiet_NaN();
  for (const char* name : {"clique", "ransac", "mac"}) {
    const auto solver = SolverRegistry::create(name);
    auto r = solver->solve(c, SolverParams{});
    EXPECT_EQ(r.status, Status::error);
    EXPECT_NE(r.message.find("correspondence 4"), std::string::npos) << r.message;
    Correspondences<3> mismatched{
        Eigen::Matrix3Xd::Zero(3, 4), Eigen::Matrix3Xd::Zero(3, 5), {}, {}};
    EXPECT_EQ(solver->solve(mismatched, SolverParams{}).status, Status::error);
    SolverParams bad;
    bad.eps = -1;
    r = solver->solve(Correspondences<3>{c.source, c.source, {}, {}}, bad);
    EXPECT_EQ(r.status, Status::error);
    EXPECT_NE(r.message.find("eps"), std::string::npos);
    const auto empty = solver->solve(Correspondences<2>{}, SolverParams{});
    EXPECT_EQ(empty.status, Status::rejected) << name;
    EXPECT_TRUE(empty.inliers.empty());
  }
}

TEST_F(Registered, CliqueReportsGraphBeyondMemoryCap) {
  Correspondences<3> c{Eigen::Matrix3Xd::Zero(3, 3000), Eigen::Matrix3Xd::Zero(3, 3000), {}, {}};
  SolverParams sp;
  sp.max_graph_bytes = 1000;
  const auto r = SolverRegistry::create("clique")->solve(c, sp);
  EXPECT_EQ(r.status, Status::error);
  EXPECT_NE(r.message.find("3000 vertices"), std::string::npos) << r.message;
}

TEST_F(Registered, CliqueTimeLimitGivesBestSoFar) {
  // Many mutually consistent outliers: all points on a tiny sphere shell make a dense graph.
  SyntheticParams p;
  p.n = 600;
  p.outlier_ratio = 1.0;
  p.extent = 0.05;
  const auto set = make_synthetic<3>(p);
  SolverParams sp;
  sp.eps = 0.03;
  sp.time_limit_s = 0.02;
  const auto r = SolverRegistry::create("clique")->solve(set.corr, sp);
  EXPECT_EQ(r.status, Status::time_limit);
  EXPECT_FALSE(r.inliers.empty());
}

TEST_F(Registered, GraphConstructionStopsAtTheTimeLimit) {
  // n = 20,000 takes far longer than a microsecond to connect: every graph solver stops in the
  // graph stage (no edges counted, nothing selected), with status time_limit, not error.
  SyntheticParams p;
  p.n = 20000;
  const auto set = make_synthetic<3>(p);
  SolverParams sp;
  sp.time_limit_s = 1e-6;
  for (const std::string name : {"clique", "mac", "jcbb"}) {
    const auto r = SolverRegistry::create(name)->solve(set.corr, sp);
    EXPECT_EQ(r.status, Status::time_limit) << name << ": " << r.message;
    EXPECT_EQ(r.counters.graph_edges, 0) << name;
    EXPECT_TRUE(r.inliers.empty()) << name;
    EXPECT_FALSE(r.accepted) << name;
    EXPECT_NE(r.message.find("building the correspondence graph"), std::string::npos) << r.message;
  }
  GraphParams gp;
  gp.time_limit_s = 1e-6;
  EXPECT_THROW(build_compatibility_graph(set.corr, gp), DeadlinePassed);
}

}  // namespace
}  // namespace verifybench

namespace verifybench {
namespace {

// --time-limit is the pair's budget (verify(): solve and null solves): every registered solver on
// n = 20,000 at 50% outliers under the calibrated rule with 0.1 s ends well within a generous
// 2 s (the exact figures, within the limit + 50 ms, are in BENCHMARK.md 27; a test does not time
// to the millisecond). Before the budget, mac took 0.63 s and jcbb 2.1 s at a 0.2 s limit here.
class Budget : public ::testing::TestWithParam<std::string> {
 protected:
  void SetUp() override { register_builtin_solvers(); }
};

TEST_P(Budget, EndsWithinThePairsTimeLimit) {
  static const LabeledSet<3> set = [] {
    SyntheticParams p;
    p.n = 20000;
    p.outlier_ratio = 0.5;
    return make_synthetic<3>(p);
  }();
  SolverParams params;
  params.time_limit_s = 0.1;
  const auto solver = SolverRegistry::create(GetParam());
  StopWatch clock;
  const Verification<3> v = verify(*solver, set.corr, params, AcceptParams{});  // pvalue: null solves too
  EXPECT_LT(clock.ms(), 2000.0) << GetParam();
  EXPECT_NE(v.result.status, Status::error) << v.result.message;
}

INSTANTIATE_TEST_SUITE_P(AllSolvers, Budget, ::testing::ValuesIn(registered_names()),
                         [](const auto& info) {
                           std::string name = info.param;
                           for (char& c : name) {
                             if (c == '-') c = '_';
                           }
                           return name;
                         });

}  // namespace
}  // namespace verifybench
