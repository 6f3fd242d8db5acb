#include "loop/evaluation.hpp"

#include <algorithm>
#include <cmath>
#include <functional>

#include "loop/backend.hpp"

namespace verifybench {

namespace {

ClosureScore score_at(const std::vector<const ClosureRow*>& rows, int positives,
                      const std::function<bool(const ClosureRow&)>& accept) {
  std::vector<bool> accepted, correct;
  for (const ClosureRow* r : rows) {
    accepted.push_back(r->record.status != Status::error && accept(*r));
    correct.push_back(r->correct);
  }
  return score_closures(accepted, correct, positives);
}

std::vector<const ClosureRow*> rows_of(const LoopRun& run, const std::string& solver) {
  std::vector<const ClosureRow*> rows;
  for (const ClosureRow& r : run.rows) {
    if (r.record.solver == solver) rows.push_back(&r);
  }
  return rows;
}

}  // namespace

void score_solvers(const LoopConfig& config, LoopRun& run) {
  const int positives = static_cast<int>(run.true_closures.size());
  for (const std::string& name : config.solvers) {
    SolverSummary sum;
    sum.solver = name;
    const std::vector<const ClosureRow*> rows = rows_of(run, name);
    sum.score = score_at(rows, positives, [](const ClosureRow& r) { return r.record.accepted; });
    int max_inliers = 0;
    bool has_p = false;
    for (const ClosureRow* r : rows) {
      sum.inliers_mean += r->record.inliers;
      sum.time_ms_mean += r->record.time_ms;
      sum.calibration_ms_mean += r->record.calibration_ms;
      max_inliers = std::max(max_inliers, r->record.inliers);
      has_p = has_p || std::isfinite(r->record.p_value);
      if (r->record.accepted) ++sum.accepted;
    }
    if (!rows.empty()) {
      sum.inliers_mean /= static_cast<double>(rows.size());
      sum.time_ms_mean /= static_cast<double>(rows.size());
      sum.calibration_ms_mean /= static_cast<double>(rows.size());
    }
    for (int K = 1; K <= max_inliers + 1; ++K) {
      const ClosureScore s =
          score_at(rows, positives, [K](const ClosureRow& r) { return r.record.inliers >= K; });
      sum.count_curve.push_back({static_cast<double>(K), s});
      if (s.fp == 0 && s.tp > 0) {
        sum.max_recall_full_precision = std::max(sum.max_recall_full_precision, s.recall);
      }
    }
    if (has_p) {
      for (int e = 1; e <= 12; ++e) {
        const double alpha = std::pow(10.0, -e);
        sum.alpha_curve.push_back({alpha, score_at(rows, positives, [alpha](const ClosureRow& r) {
                                     return std::isfinite(r.record.p_value) &&
                                            r.record.p_value < alpha;
                                   })});
      }
    }
    run.summary.push_back(std::move(sum));
  }
}

void optimise_pose_graphs(const LoopConfig& config, const std::vector<LocalMap>& maps,
                          LoopRun& run) {
  std::vector<Rigid<3>> anchors_odo;
  for (const LocalMap& m : maps) anchors_odo.push_back(m.T_world_map_odometry);
  std::vector<PoseEdge> odometry_edges;
  for (int k = 0; k + 1 < static_cast<int>(maps.size()); ++k) {
    PoseEdge e;
    e.from = k;
    e.to = k + 1;
    e.T_from_to = anchors_odo[k].inverse() * anchors_odo[k + 1];
    e.sigma = odometry_sigma(run.drift, e.T_from_to.translation().norm());
    odometry_edges.push_back(e);
  }
  // Each scan's pose from its map's anchor: T_world_anchor * (odometry anchor -> scan).
  std::vector<int> map_of_frame(run.frames.size(), 0);
  for (std::size_t i = 0, k = 0; i < run.frames.size(); ++i) {
    while (k + 1 < maps.size() && run.frames[i] > maps[k].frames.back()) ++k;
    map_of_frame[i] = static_cast<int>(k);
  }
  auto scan_poses = [&](const std::vector<Rigid<3>>& anchors) {
    std::vector<Rigid<3>> out;
    for (std::size_t i = 0; i < run.frames.size(); ++i) {
      const int k = map_of_frame[i];
      out.push_back(anchors[k] * anchors_odo[k].inverse() * run.odometry[i]);
    }
    return out;
  };
  const BackendInfo& plain_backend = find_backend("plain");
  const BackendInfo& robust_backend = find_backend("robust");
  const double deg = M_PI / 180.0;
  for (SolverSummary& sum : run.summary) {
    std::vector<PoseEdge> edges = odometry_edges;
    for (const ClosureRow* r : rows_of(run, sum.solver)) {
      if (!r->record.accepted) continue;
      PoseEdge e;
      e.from = r->match;
      e.to = r->query;
      e.T_from_to = r->T_estimate;
      e.loop = true;
      const double rot = config.loop_sigma_rot_deg * deg, tr = config.loop_sigma_trans;
      if (r->record.dim == 2) {  // a planar estimate says nothing of z, roll and pitch
        e.sigma << 0.5, 0.5, rot, tr, tr, 10.0;
      } else {
        e.sigma << rot, rot, rot, tr, tr, tr;
      }
      edges.push_back(e);
    }
    sum.loop_edges = static_cast<int>(edges.size() - odometry_edges.size());
    const PoseGraphResult plain = plain_backend.solve(anchors_odo, edges);
    const PoseGraphResult robust = robust_backend.solve(anchors_odo, edges);
    sum.graph_iterations = plain.iterations;
    sum.graph_iterations_robust = robust.iterations;
    sum.graph_converged = plain.converged;
    sum.graph_converged_robust = robust.converged;
    sum.poses_with = scan_poses(plain.poses);
    sum.poses_with_robust = scan_poses(robust.poses);
  }
}

void trajectory_errors(const LoopConfig& config, LoopRun& run) {
  run.ape_without = absolute_pose_error(run.odometry, run.truth);
  for (SolverSummary& sum : run.summary) {
    sum.ape_with = absolute_pose_error(sum.poses_with, run.truth);
    sum.ape_with_robust = absolute_pose_error(sum.poses_with_robust, run.truth);
  }
  if (config.relations.empty()) return;
  std::vector<double> stamps;  // the frames' (config.stamps is per frame of the excerpt)
  for (int f : run.frames) stamps.push_back(config.stamps.at(static_cast<std::size_t>(f)));
  auto error_of = [&](const std::vector<Rigid<3>>& poses) {
    return relation_error(config.relations, stamps, poses, config.odometry_stream_stamps,
                          config.odometry_stream);
  };
  run.relations_without = error_of(run.odometry);
  for (SolverSummary& sum : run.summary) {
    sum.relations_with = error_of(sum.poses_with);
    sum.relations_with_robust = error_of(sum.poses_with_robust);
  }
}

void summarise_solvers(const LoopConfig& config, const std::vector<LocalMap>& maps, LoopRun& run) {
  score_solvers(config, run);
  optimise_pose_graphs(config, maps, run);
  trajectory_errors(config, run);
}

}  // namespace verifybench
