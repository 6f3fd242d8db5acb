// JCBB and its chi-square gates against oracles: published chi-square quantiles, closed forms of
// the CDF, a brute-force search over every subset of a small set for the largest jointly
// compatible one, and drawn transforms.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>

#include "core/chi2.hpp"
#include "core/metrics.hpp"
#include "core/rigid_fit.hpp"
#include "generators/synthetic.hpp"
#include "harness/builtin.hpp"
#include "solvers/registry.hpp"

namespace verifybench {
namespace {

TEST(Chi2, QuantilesMatchPublishedTables) {
  // Critical values from standard chi-square tables (e.g. NIST/SEMATECH e-Handbook, 1.3.6.7.4).
  struct Row {
    int dof;
    double p, x;
  };
  for (const Row& r :
       {Row{1, 0.95, 3.841}, Row{2, 0.95, 5.991}, Row{3, 0.95, 7.815}, Row{6, 0.95, 12.592},
        Row{10, 0.95, 18.307}, Row{30, 0.95, 43.773}, Row{100, 0.95, 124.342}, Row{3, 0.99, 11.345},
        Row{20, 0.90, 28.412}, Row{5, 0.05, 1.145}}) {
    EXPECT_NEAR(chi2_quantile(r.p, r.dof), r.x, 1e-3) << "dof " << r.dof << " p " << r.p;
  }
}

TEST(Chi2, CdfMatchesClosedForms) {
  // dof 2: 1 - exp(-x/2); dof 1: erf(sqrt(x/2)).
  for (double x : {0.01, 0.5, 1.0, 3.0, 10.0, 40.0}) {
    EXPECT_NEAR(chi2_cdf(x, 2), 1.0 - std::exp(-x / 2), 1e-13) << x;
    EXPECT_NEAR(chi2_cdf(x, 1), std::erf(std::sqrt(x / 2)), 1e-13) << x;
  }
  EXPECT_THROW(chi2_quantile(1.0, 3), std::invalid_argument);
  EXPECT_THROW(chi2_quantile(0.5, 0), std::invalid_argument);
}

/// The definition: the residual test of the least-squares fit, for one subset.
template <int Dim>
bool jointly_compatible(const Correspondences<Dim>& c, const std::vector<int>& h, double sigma,
                        double p) {
  const int k = static_cast<int>(h.size());
  const int dof = Dim == 3 ? (k <= 1 ? 0 : k == 2 ? 1 : 3 * k - 6) : (k <= 1 ? 0 : 2 * k - 3);
  if (dof == 0) return true;
  if (k == 2) {  // the best fit aligns the midpoints and the directions: e = (d_m - d_q)^2 / 2
    const double d = (c.source.col(h[0]) - c.source.col(h[1])).norm() -
                     (c.target.col(h[0]) - c.target.col(h[1])).norm();
    return d * d / 2 / (2 * sigma * sigma) < chi2_quantile(p, 1);
  }
  const auto T = fit_rigid(c, h);
  if (!T) return false;
  double e = 0.0;
  for (int i : h) e += (*T * c.source.col(i) - c.target.col(i)).squaredNorm();
  return e / (2 * sigma * sigma) < chi2_quantile(p, dof);
}

TEST(Jcbb, NoPriorFindsTheLargestJointlyCompatibleSetOfBruteForce) {
  // 12 matches, all 4096 subsets. JCBB without a prior accepts H when H's members are pairwise
  // compatible (the |H| = 2 test) and every prefix of H in its documented search order (degree
  // in the pair graph, descending, ties by index) passes the joint test; the oracle enumerates
  // exactly that definition and takes the largest.
  register_builtin_solvers();
  const double sigma = 0.05, p = 0.95;
  const double pair_eps = 2 * sigma * std::sqrt(chi2_quantile(p, 1));
  for (std::uint64_t seed = 1; seed <= 8; ++seed) {
    SyntheticParams sp;
    sp.n = 12;
    sp.outlier_ratio = 0.5;
    sp.noise = 0.03;
    sp.extent = 2.0;  // small scene: outliers are often nearly compatible
    sp.seed = seed;
    const auto set = make_synthetic<3>(sp);
    const auto& c = set.corr;
    auto pair_ok = [&](int a, int b) {
      return std::abs((c.source.col(a) - c.source.col(b)).norm() -
                      (c.target.col(a) - c.target.col(b)).norm()) < pair_eps;
    };
    std::vector<int> degree(12, 0), order(12);
    for (int a = 0; a < 12; ++a)
      for (int b = 0; b < 12; ++b) degree[a] += a != b && pair_ok(a, b);
    std::iota(order.begin(), order.end(), 0);
    std::stable_sort(order.begin(), order.end(),
                     [&](int a, int b) { return degree[a] > degree[b]; });
    std::size_t best = 0;
    for (unsigned mask = 1; mask < (1u << 12); ++mask) {
      std::vector<int> h;  // in search order
      for (int v : order)
        if (mask >> v & 1u) h.push_back(v);
      if (h.size() <= best) continue;
      bool ok = true;
      for (std::size_t a = 0; a < h.size() && ok; ++a)
        for (std::size_t b = a + 1; b < h.size() && ok; ++b) ok = pair_ok(h[a], h[b]);
      for (std::size_t k = 1; k <= h.size() && ok; ++k) {
        ok = jointly_compatible(c, std::vector<int>(h.begin(), h.begin() + k), sigma, p);
      }
      if (ok) best = h.size();
    }
    SolverParams params;
    params.jcbb.sigma = sigma;
    params.jcbb.confidence = p;
    params.min_inliers = 1;
    const auto r = SolverRegistry::create("jcbb")->solve(c, params);
    ASSERT_EQ(r.status, Status::ok);
    EXPECT_EQ(r.inliers.size(), best) << "seed " << seed;
    EXPECT_TRUE(jointly_compatible(c, r.inliers, sigma, p)) << "seed " << seed;
  }
}

template <int Dim>
void recovers_with_and_without_prior() {
  register_builtin_solvers();
  for (double ratio : {0.5, 0.9}) {
    for (bool prior : {false, true}) {
      SyntheticParams sp;
      sp.n = 300;
      sp.outlier_ratio = ratio;
      sp.seed = 5;
      auto set = make_synthetic<Dim>(sp);
      if (prior) add_pose_prior(set, 0.03, 0.3, 9);
      const auto r = SolverRegistry::create("jcbb")->solve(set.corr, SolverParams{});
      ASSERT_EQ(r.status, Status::ok) << ratio << " prior " << prior << " " << r.message;
      EXPECT_LT(rotation_error_deg(r.T_target_source, *set.truth.T_target_source), 0.5);
      EXPECT_LT(translation_error(r.T_target_source, *set.truth.T_target_source), 0.05);
      const auto q = inlier_scores(r.inliers, set.truth.labels);
      EXPECT_EQ(q.precision, 1.0) << ratio << " prior " << prior;
      EXPECT_GT(q.recall, 0.9) << ratio << " prior " << prior;
    }
  }
}

TEST(Jcbb, RecoversDrawnMotionsWithAndWithoutPrior2D) { recovers_with_and_without_prior<2>(); }
TEST(Jcbb, RecoversDrawnMotionsWithAndWithoutPrior3D) { recovers_with_and_without_prior<3>(); }

TEST(Jcbb, APriorGatesOutWhatItRulesOut) {
  // A repetitive scene: outliers are copies shifted 1-2 pillars (2-4 m) along the corridor and
  // outnumber the inliers, so without a prior the largest compatible set is a wrong copy; a prior
  // with 0.3 m translation sigma rules the shifted copies out individually.
  register_builtin_solvers();
  SyntheticParams sp;
  sp.kind = "repetitive";
  sp.n = 400;
  sp.outlier_ratio = 0.85;
  sp.seed = 3;
  auto set = make_synthetic<3>(sp);
  const auto blind = SolverRegistry::create("jcbb")->solve(set.corr, SolverParams{});
  EXPECT_GT(translation_error(blind.T_target_source, *set.truth.T_target_source), 1.0);
  add_pose_prior(set, 0.01, 0.3, 4);
  const auto guided = SolverRegistry::create("jcbb")->solve(set.corr, SolverParams{});
  EXPECT_LT(translation_error(guided.T_target_source, *set.truth.T_target_source), 0.05);
  EXPECT_EQ(inlier_scores(guided.inliers, set.truth.labels).precision, 1.0);
}

TEST(Jcbb, TimeLimitReturnsTheBestSoFar) {
  register_builtin_solvers();
  SyntheticParams sp;
  sp.n = 600;
  sp.outlier_ratio = 1.0;
  sp.extent = 0.6;  // most pairs compatible, few large sets jointly: an exponential tree
  const auto set = make_synthetic<3>(sp);
  SolverParams params;
  params.time_limit_s = 0.05;
  params.jcbb.sigma = 0.05;
  const auto r = SolverRegistry::create("jcbb")->solve(set.corr, params);
  EXPECT_EQ(r.status, Status::time_limit);
  EXPECT_FALSE(r.inliers.empty());
}

TEST(Jcbb, BadPriorCovarianceIsAnError) {
  register_builtin_solvers();
  SyntheticParams sp;
  sp.n = 30;
  auto set = make_synthetic<3>(sp);
  add_pose_prior(set, 0.01, 0.1, 1);
  set.corr.prior->covariance(0, 0) = -1.0;
  const auto r = SolverRegistry::create("jcbb")->solve(set.corr, SolverParams{});
  EXPECT_EQ(r.status, Status::error);
  EXPECT_NE(r.message.find("positive definite"), std::string::npos) << r.message;
}

}  // namespace
}  // namespace verifybench
