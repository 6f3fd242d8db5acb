#include "loop/consistency.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "cliques/max_clique.hpp"
#include "core/chi2.hpp"
#include "graph/bitgraph.hpp"

namespace verifybench {

namespace {

/// O(i, j) = X_i^-1 X_j of the odometry poses.
Rigid<3> odometry_between(const std::vector<LocalMap>& maps, int i, int j) {
  return maps[i].T_world_map_odometry.inverse() * maps[j].T_world_map_odometry;
}

}  // namespace

void ConsistencyParams::validate() const {
  if (!(confidence >= 0.0 && confidence < 1.0)) {
    throw std::invalid_argument("loop consistency: confidence must be in [0, 1), got " +
                                std::to_string(confidence));
  }
}

const std::vector<ParamRow<ConsistencyParams>>& consistency_param_rows() {
  using P = ConsistencyParams;
  static const std::vector<ParamRow<P>> rows = {field_row(
      &P::confidence, "loop-consistency", "loop_consistency", "C",
      "after the accept rule and the dense check, keep per solver only the largest set of accepted "
      "closures that pairwise agree through the odometry between their maps (PCM: each pair's "
      "cycle within the chi-square gate at confidence C, drift-model and loop-edge sigmas); "
      "0 = off",
      0.0, 0.999999, "a value in [0, 1) (0 = off)")};
  return rows;
}

double cycle_d2(const LoopMeasurement& a, const LoopMeasurement& b,
                const std::vector<LocalMap>& maps, const ConsistencyModel& model) {
  // E = O(qa, qb)^-1 * Z_a^-1 * O(ma, mb) * Z_b: the identity when both closures are right.
  const Rigid<3> E = odometry_between(maps, a.query, b.query).inverse() *
                     a.T_match_query.inverse() * odometry_between(maps, a.match, b.match) *
                     b.T_match_query;
  const double theta = Eigen::AngleAxisd(E.rotation()).angle();
  const double t = E.translation().norm();
  const double sq = map_travel(maps, a.query, b.query);
  const double sm = map_travel(maps, a.match, b.match);
  const Eigen::Matrix<double, 6, 1> s_q = odometry_sigma(model.drift, sq);
  const Eigen::Matrix<double, 6, 1> s_m = odometry_sigma(model.drift, sm);
  const double loop_rot = model.loop_sigma_rot_deg * M_PI / 180.0;
  // (roll, pitch, yaw, x, y, z): the yaw walk dominates the drift model's rotation (in 3D its
  // sigma stands for every axis, and the largest axis's translation sigma for each: a gate at
  // least as wide as the stated confidence).
  const double var_theta = s_q(2) * s_q(2) + s_m(2) * s_m(2) + 2.0 * loop_rot * loop_rot;
  const double trans_q = s_q.tail<3>().head(model.dim == 2 ? 2 : 3).maxCoeff();
  const double trans_m = s_m.tail<3>().head(model.dim == 2 ? 2 : 3).maxCoeff();
  // Rotation errors swing what follows them in E: a loop's rotation swings the rest of the cycle
  // up to the other loop's end (|t(O_m Z_b) - t(Z_a)|, and the same with a and b swapped); the
  // end of an odometry segment's yaw swings the loop that leaves it (|t(Z)|). (odometry_sigma
  // already holds the swing within a segment.)
  const double cycle_lever = std::max(
      ((odometry_between(maps, a.match, b.match) * b.T_match_query).translation() -
       a.T_match_query.translation())
          .norm(),
      ((odometry_between(maps, b.match, a.match) * a.T_match_query).translation() -
       b.T_match_query.translation())
          .norm());
  const double loop_lever = std::max(a.T_match_query.translation().norm(),
                                     b.T_match_query.translation().norm());
  const double var_t = trans_q * trans_q + trans_m * trans_m +
                       2.0 * model.loop_sigma_trans * model.loop_sigma_trans +
                       loop_rot * loop_rot * cycle_lever * cycle_lever +
                       (s_q(2) * s_q(2) + s_m(2) * s_m(2)) * loop_lever * loop_lever;
  return theta * theta / var_theta + t * t / var_t;
}

ConsistentSet consistent_set(const std::vector<LoopMeasurement>& loops,
                             const std::vector<LocalMap>& maps, const ConsistencyModel& model,
                             const ConsistencyParams& params, double time_limit_s) {
  const int n = static_cast<int>(loops.size());
  ConsistentSet out;
  for (int i = 0; i < n; ++i) out.kept.push_back(i);
  if (n < 2 || params.confidence <= 0.0) return out;
  const double gate = chi2_quantile(params.confidence, model.dim == 2 ? 3 : 6);
  BitGraph g(n);
  for (int i = 0; i < n; ++i) {
    for (int j = i + 1; j < n; ++j) {
      if (cycle_d2(loops[static_cast<std::size_t>(i)], loops[static_cast<std::size_t>(j)], maps,
                   model) <= gate) {
        g.add_edge(i, j);
      }
    }
  }
  CliqueSearchParams search;
  search.time_limit_s = time_limit_s;
  const CliqueSearchResult found = max_clique(g, search);
  out.kept = found.clique;
  out.proven = !found.stopped;
  if (out.kept.empty()) out.kept.push_back(0);  // no edge: any one closure is a set of one
  std::sort(out.kept.begin(), out.kept.end());
  return out;
}

}  // namespace verifybench
