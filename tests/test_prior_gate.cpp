// The pose prior's gate of the calibrated rule (issue #13): the perturbation and d^2 against hand
// formulas, the chi-square gate against tabulated quantiles, and the decisions it changes: a
// motion far from the prior is not accepted under the pvalue rule, the same motion is without the
// gate and under the paper's count rule, and a prior around the truth leaves loops accepted.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <random>

#include "acceptance/prior_gate.hpp"
#include "core/random.hpp"
#include "generators/synthetic.hpp"
#include "harness/harness.hpp"
#include "registered_solvers.hpp"
#include "reports/report.hpp"
#include "solvers/registry.hpp"

namespace verifybench {
namespace {

Rigid<3> rigid3(const Eigen::Vector3d& w, const Eigen::Vector3d& v) {
  Rigid<3> T = Rigid<3>::Identity();
  if (w.norm() > 0) T.linear() = Eigen::AngleAxisd(w.norm(), w.normalized()).toRotationMatrix();
  T.translation() = v;
  return T;
}

TEST(PriorGate, PerturbationAndDistanceFollowTheirDefinitions) {
  // T = E T0 with E = (rotation vector w, translation v): the perturbation is (w, v), and with a
  // diagonal P, d^2 = sum of delta_k^2 / P_kk.
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int rep = 0; rep < 50; ++rep) {
    const Rigid<3> T0 = rigid3({u(rng), u(rng), u(rng)}, {20 * u(rng), 20 * u(rng), u(rng)});
    const Eigen::Vector3d w = Eigen::Vector3d(u(rng), u(rng), u(rng)).normalized() * 3.0 *
                              std::abs(u(rng));  // angles up to 3 rad < pi
    const Eigen::Vector3d v(30 * u(rng), 30 * u(rng), 2 * u(rng));
    const Rigid<3> T = rigid3(w, v) * T0;
    const Eigen::Matrix<double, 6, 1> delta = prior_perturbation<3>(T, T0);
    EXPECT_LT((delta.head<3>() - w).norm(), 1e-9) << rep;
    EXPECT_LT((delta.tail<3>() - v).norm(), 1e-9) << rep;

    Correspondences<3> corr;
    EXPECT_FALSE(prior_distance2(corr, T).has_value());  // no prior, no distance
    PosePrior<3> prior;
    prior.T_target_source = T0;
    const Eigen::Matrix<double, 6, 1> sd = (Eigen::Matrix<double, 6, 1>() << 0.1, 0.2, 0.05, 1, 2, 0.5).finished();
    prior.covariance = sd.cwiseAbs2().asDiagonal();
    corr.prior = prior;
    double hand = 0.0;
    for (int k = 0; k < 3; ++k) hand += w(k) * w(k) / (sd(k) * sd(k));
    for (int k = 0; k < 3; ++k) hand += v(k) * v(k) / (sd(3 + k) * sd(3 + k));
    EXPECT_NEAR(*prior_distance2(corr, T), hand, 1e-9 * hand) << rep;
  }
  // 2D: (theta, x, y), theta in (-pi, pi].
  Rigid<2> T0 = Rigid<2>::Identity();
  T0.linear() = Eigen::Rotation2Dd(2.5).toRotationMatrix();
  T0.translation() = Eigen::Vector2d(4, -7);
  Rigid<2> E = Rigid<2>::Identity();
  E.linear() = Eigen::Rotation2Dd(-1.25).toRotationMatrix();
  E.translation() = Eigen::Vector2d(-3, 0.5);
  const Eigen::Vector3d delta = prior_perturbation<2>(E * T0, T0);
  EXPECT_NEAR(delta(0), -1.25, 1e-12);
  EXPECT_NEAR(delta(1), -3.0, 1e-12);
  EXPECT_NEAR(delta(2), 0.5, 1e-12);
}

TEST(PriorGate, GateIsTheChiSquareQuantile) {
  // Tabulated: chi-square 99.9% points, 22.458 for 6 dof, 16.266 for 3; 95%: 12.592, 7.815.
  EXPECT_TRUE(inside_prior_gate<3>(22.45, 0.999));
  EXPECT_FALSE(inside_prior_gate<3>(22.47, 0.999));
  EXPECT_TRUE(inside_prior_gate<2>(16.26, 0.999));
  EXPECT_FALSE(inside_prior_gate<2>(16.28, 0.999));
  EXPECT_TRUE(inside_prior_gate<3>(12.58, 0.95));
  EXPECT_FALSE(inside_prior_gate<3>(12.60, 0.95));
  EXPECT_TRUE(inside_prior_gate<2>(7.81, 0.95));
  EXPECT_FALSE(inside_prior_gate<2>(7.82, 0.95));
}

template <int Dim>
LabeledSet<Dim> loop_set(std::uint64_t seed) {
  SyntheticParams sp;
  sp.n = 300;
  sp.outlier_ratio = 0.5;
  sp.seed = seed;
  return make_synthetic<Dim>(sp);
}

/// The set's prior moved off the truth by E = (turned by `yaw` about z, shifted by `shift` m along
/// x), with sigmas of 5 deg and 1 m.
template <int Dim>
void prior_off_the_truth(LabeledSet<Dim>& set, double yaw, double shift) {
  PosePrior<Dim> prior;
  Rigid<Dim> E = Rigid<Dim>::Identity();
  if constexpr (Dim == 2) {
    E.linear() = Eigen::Rotation2Dd(yaw).toRotationMatrix();
  } else {
    E.linear() = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  }
  E.translation()(0) = shift;
  prior.T_target_source = E * *set.truth.T_target_source;
  prior.covariance.setIdentity();
  constexpr int kRot = Dim == 2 ? 1 : 3;
  prior.covariance.template topLeftCorner<kRot, kRot>() *= std::pow(5.0 * M_PI / 180.0, 2);
  set.corr.prior = prior;
}

template <int Dim>
void expect_gate_decisions() {
  const SuccessCriteria criteria;
  int checked = 0;
  for (const char* name : {"clique", "ransac"}) {
    const auto solver = SolverRegistry::create(name);
    for (std::uint64_t seed = 1; seed <= 3; ++seed) {
      SolverParams params;
      params.seed = derive_seed(seed, {4});
      const AcceptParams accept;  // the default: pvalue, with the gate
      const std::string label = std::string(name) + " " + std::to_string(Dim) + "D seed " +
                                std::to_string(seed);
      // A prior around the truth (2 deg, 0.5 m): the loop is accepted, d^2 within the gate.
      LabeledSet<Dim> near = loop_set<Dim>(seed);
      add_pose_prior(near, 2.0 * M_PI / 180.0, 0.5, seed);
      const TrialRecord a = evaluate(*solver, name, near, params, accept, criteria);
      ASSERT_TRUE(a.success.value_or(false)) << label;
      EXPECT_TRUE(a.accepted) << label;
      EXPECT_LE(a.prior_d2, 22.46) << label;
      // The same motion against a prior turned by 90 deg and shifted by 20 m (sigmas 5 deg, 1 m):
      // d^2 >= (90 / 5)^2 + 20^2 (the fit is within 15 deg and 0.3 m of the truth), rejected.
      LabeledSet<Dim> far = loop_set<Dim>(seed);
      prior_off_the_truth(far, M_PI / 2, 20.0);
      const TrialRecord b = evaluate(*solver, name, far, params, accept, criteria);
      ASSERT_LT(b.rotation_error_deg, 15.0) << label;  // the right motion, however decided
      ASSERT_LT(b.translation_error, 0.3) << label;
      EXPECT_GT(b.prior_d2, std::pow(75.0 / 5.0, 2) + std::pow(19.7, 2)) << label;
      EXPECT_FALSE(b.accepted) << label;
      EXPECT_STREQ(decision_of(b), "FN") << label;
      EXPECT_LT(b.p_value, accept.alpha) << label;  // the null alone would accept
      // Without the gate, and under the paper's count rule, the prior does not decide.
      AcceptParams ungated = accept;
      ungated.prior_gate = 0.0;
      EXPECT_TRUE(evaluate(*solver, name, far, params, ungated, criteria).accepted) << label;
      AcceptParams count = accept;
      count.rule = AcceptParams::Rule::count;
      const TrialRecord c = evaluate(*solver, name, far, params, count, criteria);
      EXPECT_TRUE(c.accepted) << label;
      EXPECT_EQ(c.prior_d2, b.prior_d2) << label;  // recorded under either rule
      // No prior: no distance.
      EXPECT_TRUE(std::isnan(evaluate(*solver, name, loop_set<Dim>(seed), params, accept, criteria).prior_d2))
          << label;
      ++checked;
    }
  }
  EXPECT_EQ(checked, 6);
}

TEST(PriorGate, MotionsFarFromThePriorAreNotAccepted) {
  expect_gate_decisions<2>();
  expect_gate_decisions<3>();
}

}  // namespace
}  // namespace verifybench
