// Draws a set with a known motion, verifies it with the registry's `clique` solver and checks the
// estimate against the drawn motion: exit 0 only when the installed library works end to end.
#include <cstdio>
#include <verifybench/generators/synthetic.hpp>
#include <verifybench/harness/builtin.hpp>
#include <verifybench/solvers/registry.hpp>
#include <verifybench/version.hpp>

int main() {
  namespace vb = verifybench;
  vb::register_builtin_solvers();
  vb::SyntheticParams p;
  p.n = 300;
  p.outlier_ratio = 0.9;
  p.seed = 3;
  const auto set = vb::make_synthetic<3>(p);
  const auto result = vb::SolverRegistry::create("clique")->solve(set.corr, vb::SolverParams{});
  const auto error = (result.T_target_source.matrix() - set.truth.T_target_source->matrix()).norm();
  std::printf("verifybench %s: clique status %s, %zu inliers, |T - T_true| = %.4f\n", vb::kVersion,
              vb::to_string(result.status), result.inliers.size(), error);
  return result.status == vb::Status::ok && error < 0.05 ? 0 : 1;
}
