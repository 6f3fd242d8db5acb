#include "loop/sequence.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <numeric>
#include <optional>
#include <stdexcept>
#include <variant>

#include "core/metrics.hpp"
#include "core/parallel.hpp"
#include "core/random.hpp"
#include "core/timer.hpp"
#include "frontend/cloud_io.hpp"
#include "harness/harness.hpp"
#include "solvers/registry.hpp"

namespace verifybench {

void LoopConfig::validate() const {
  auto positive = [](const char* name, double v) {
    if (!(v > 0.0) || !std::isfinite(v)) {
      throw std::invalid_argument(std::string("loop: ") + name +
                                  " must be a positive number, got " + std::to_string(v));
    }
  };
  if (truth.size() < 2) {
    throw std::invalid_argument("loop: the trajectory has " + std::to_string(truth.size()) +
                                " poses (at least 2)");
  }
  positive("scan_spacing", scan_spacing);
  positive("gt_max_distance", gt_max_distance);
  positive("pose_tolerance", pose_tolerance);
  positive("loop_sigma_trans", loop_sigma_trans);
  positive("loop_sigma_rot_deg", loop_sigma_rot_deg);
  if (!(gt_overlap > 0.0 && gt_overlap <= 1.0)) {
    throw std::invalid_argument("loop: gt_overlap must be in (0, 1], got " +
                                std::to_string(gt_overlap));
  }
  if (extract.pipeline != "3d" && extract.pipeline != "2d") {
    throw std::invalid_argument("loop: pipeline '" + extract.pipeline +
                                "' (loop closure retrieves by binary descriptors: 3d or 2d)");
  }
  if (solvers.empty()) throw std::invalid_argument("loop: no solver");
  if (odometry != "drift" && odometry != "gicp") {
    throw std::invalid_argument("loop: odometry '" + odometry + "' is not drift or gicp");
  }
  if (odometry == "gicp") gicp.validate();
  SolverRegistry::check(solvers);
  maps.validate();
  retrieval.validate();
  drift.validate();
  params.validate();
  if (sequence_dir.empty()) {
    world.validate();
    lidar.validate();
  }
}

ExtractParams loop_extract_defaults() {
  ExtractParams p;
  p.matching.kind = MatchingPolicy::Kind::nearest;
  p.p2.bev.range = 80.0;
  return p;
}

Rigid<3> lift_planar(const Rigid<2>& T) {
  Rigid<3> out = Rigid<3>::Identity();
  out.linear().topLeftCorner<2, 2>() = T.linear();
  out.translation().head<2>() = T.translation();
  return out;
}

std::vector<int> select_frames(const Trajectory& truth, double spacing) {
  std::vector<int> frames;
  if (truth.empty()) return frames;
  frames.push_back(0);
  double travelled = 0.0;
  for (std::size_t i = 1; i < truth.size(); ++i) {
    travelled += (truth[i].translation() - truth[i - 1].translation()).norm();
    if (travelled >= spacing) {
      frames.push_back(static_cast<int>(i));
      travelled = 0.0;
    }
  }
  return frames;
}

std::vector<TrueClosure> true_closures(const std::vector<LocalMap>& maps, int min_map_gap,
                                       double max_distance, double min_overlap) {
  std::vector<TrueClosure> out;
  for (std::size_t q = 0; q < maps.size(); ++q) {
    for (std::size_t m = 0; m + min_map_gap <= q; ++m) {
      const double d = (maps[q].T_world_map_truth.translation() -
                        maps[m].T_world_map_truth.translation()).norm();
      if (d >= max_distance) continue;
      const double overlap = overlap_ratio(maps[q].occupancy, maps[m].occupancy);
      if (overlap > min_overlap) {
        out.push_back({static_cast<int>(q), static_cast<int>(m), overlap, d});
      }
    }
  }
  return out;
}

namespace {

// Sigmas of the odometry between two anchors `length` metres apart under the drift model: the
// per-axis translation noise adds up to at most trans_rel * L, the yaw walk's sigma is
// yaw * sqrt(L) and swings the end point sideways by about that times L / sqrt(3).
Eigen::Matrix<double, 6, 1> odometry_sigma(const DriftParams& d, double length) {
  const double deg = M_PI / 180.0, L = std::max(length, 1.0);
  const double yaw = std::max(d.yaw_deg * deg * std::sqrt(L), 1e-4);
  const double tilt = std::max(d.tilt_deg * deg * std::sqrt(L), 1e-4);
  const double trans = std::max(std::hypot(d.trans_rel * L, yaw * L / std::sqrt(3.0)), 0.05);
  Eigen::Matrix<double, 6, 1> s;
  s << tilt, tilt, yaw, trans, trans, trans;
  return s;
}

ClosureScore score_at(const std::vector<const ClosureRow*>& rows, int positives,
                      const std::function<bool(const ClosureRow&)>& accept) {
  std::vector<bool> accepted, correct;
  for (const ClosureRow* r : rows) {
    accepted.push_back(r->record.status != "error" && accept(*r));
    correct.push_back(r->correct);
  }
  return score_closures(accepted, correct, positives);
}

}  // namespace

LoopRun run_loop(const LoopConfig& config, const LoopProgress& progress) {
  config.validate();
  auto report = [&](const std::string& stage, long long done, long long total) {
    if (progress) progress(stage, done, total);
  };
  StopWatch total_clock;
  LoopRun run;
  const Trajectory& truth = config.truth;
  run.frames = select_frames(truth, config.scan_spacing);
  if (run.frames.size() < 3) {
    throw std::invalid_argument("loop: " + std::to_string(run.frames.size()) +
                                " scans at this spacing (at least 3)");
  }

  // Scans: simulated or read.
  StopWatch clock;
  std::unique_ptr<LidarSimulator> lidar;
  if (config.sequence_dir.empty()) {
    WorldParams wp = config.world;
    wp.seed = derive_seed(config.seed, {1});
    const World world = build_street_world(truth, wp);
    run.world = world.counts;
    lidar = std::make_unique<LidarSimulator>(world.mesh);
  }
  run.seconds["world_s"] = clock.ms() / 1000.0;
  const ScanSource scans = [&](int frame) -> std::vector<Eigen::Vector3f> {
    if (lidar) {
      return lidar->scan(truth[frame], config.lidar,
                         derive_seed(config.seed, {2, static_cast<std::uint64_t>(frame)}));
    }
    char name[32];
    std::snprintf(name, sizeof name, "%06d.bin", config.first_frame + frame);
    return read_cloud(config.sequence_dir + "/velodyne/" + name);
  };

  // Odometry: the drift model, or GICP from scan to scan (sequential: each step starts from the
  // last). Only the frames used are filled in.
  clock = StopWatch();
  Trajectory odometry_all;
  if (config.odometry == "gicp") {
    odometry_all.assign(truth.size(), Rigid<3>::Identity());
    const int n = static_cast<int>(run.frames.size());
    long long steps = 0;
    const auto poses = gicp_odometry([&](int k) { return scans(run.frames[k]); }, n,
                                     truth[run.frames[0]], config.gicp,
                                     [&] { report("odometry", ++steps, n - 1); });
    for (int k = 0; k < n; ++k) odometry_all[run.frames[k]] = poses[k];
  } else {
    odometry_all = drift_odometry(truth, config.drift, derive_seed(config.seed, {3}));
  }
  for (int f : run.frames) {
    run.truth.push_back(truth[f]);
    run.odometry.push_back(odometry_all[f]);
  }
  run.seconds["odometry_s"] = clock.ms() / 1000.0;

  // Local maps and their features, in parallel over maps (each map's work is its own).
  clock = StopWatch();
  const auto groups = partition_maps(odometry_all, run.frames, config.maps.map_length);
  const int n_maps = static_cast<int>(groups.size());
  std::vector<LocalMap> maps(n_maps);
  std::vector<Features> features(n_maps);
  std::vector<double> feature_ms(n_maps, 0.0), map_ms(n_maps, 0.0);
  {
    WorkerPool pool(config.threads);
    std::mutex mutex;
    long long done = 0;
    pool.parallel_for(n_maps, [&](int k) {
      StopWatch c;
      maps[k] = build_local_map(k, groups[k], odometry_all, truth, scans, config.maps);
      map_ms[k] = c.ms();
      c = StopWatch();
      features[k] = extract_features(maps[k].points, config.extract);
      feature_ms[k] = c.ms();
      std::lock_guard<std::mutex> lock(mutex);
      report("maps", ++done, n_maps);
    });
  }
  run.seconds["maps_s"] = std::accumulate(map_ms.begin(), map_ms.end(), 0.0) / 1000.0;
  run.seconds["features_s"] = std::accumulate(feature_ms.begin(), feature_ms.end(), 0.0) / 1000.0;
  run.seconds["maps_wall_s"] = clock.ms() / 1000.0;
  for (const LocalMap& m : maps) {
    MapInfo info;
    info.index = m.index;
    info.first_frame = m.frames.front();
    info.last_frame = m.frames.back();
    info.anchor = m.anchor;
    info.scans = static_cast<int>(m.frames.size());
    info.points = static_cast<int>(m.points.size());
    info.keypoints = static_cast<int>(features[m.index].points.size());
    info.occupied_cells = static_cast<int>(m.occupancy.size());
    info.position_truth = m.T_world_map_truth.translation();
    run.maps.push_back(info);
  }

  // Ground truth and retrieval.
  clock = StopWatch();
  run.true_closures = true_closures(maps, config.retrieval.min_map_gap, config.gt_max_distance,
                                    config.gt_overlap);
  RetrievalParams rp = config.retrieval;
  rp.max_hamming = config.extract.max_hamming;
  run.candidates = retrieve_candidates(features, rp);
  run.seconds["retrieval_s"] = clock.ms() / 1000.0;

  // Verification: every solver on every candidate pair.
  clock = StopWatch();
  std::vector<std::unique_ptr<Solver>> solvers;
  for (const auto& name : config.solvers) solvers.push_back(SolverRegistry::create(name));
  const long long total_solves =
      static_cast<long long>(run.candidates.size()) * static_cast<long long>(solvers.size());
  long long solves = 0;
  for (const Candidate& c : run.candidates) {
    const LocalMap& q = maps[c.query];
    const LocalMap& m = maps[c.match];
    const Rigid<3> T_truth = m.T_world_map_truth.inverse() * q.T_world_map_truth;
    ExtractParams ep = config.extract;
    ep.seed = derive_seed(config.seed, {4, static_cast<std::uint64_t>(c.query),
                                        static_cast<std::uint64_t>(c.match)});
    Dump dump = match_features(features[c.query], features[c.match], T_truth, ep);
    double overlap = overlap_ratio(q.occupancy, m.occupancy);
    bool is_true = false;
    for (const TrueClosure& t : run.true_closures) {
      if (t.query == c.query && t.match == c.match) is_true = true;
    }
    SolverParams sp = config.params;
    sp.seed = derive_seed(config.seed, {5, static_cast<std::uint64_t>(c.query),
                                        static_cast<std::uint64_t>(c.match)});
    for (std::size_t s = 0; s < solvers.size(); ++s) {
      ClosureRow row;
      row.query = c.query;
      row.match = c.match;
      row.votes = c.votes;
      row.overlap = overlap;
      row.true_closure = is_true;
      row.T_truth = T_truth;
      std::visit(
          [&](auto& set) {
            constexpr int Dim = std::decay_t<decltype(set.corr.source)>::RowsAtCompileTime;
            set.truth.positive = is_true;
            if (set.corr.empty()) {
              row.record.solver = config.solvers[s];
              row.record.dim = Dim;
              row.record.status = "rejected";
              row.record.message = "no correspondence";
              return;
            }
            row.record = evaluate<Dim>(*solvers[s], config.solvers[s], set, sp, SuccessCriteria{});
            Eigen::Matrix<double, Dim + 1, Dim + 1> M;
            for (int i = 0; i <= Dim; ++i) {
              for (int j = 0; j <= Dim; ++j) {
                M(i, j) = row.record.T_target_source.empty()
                              ? (i == j ? 1.0 : 0.0)
                              : row.record.T_target_source[i * (Dim + 1) + j];
              }
            }
            Rigid<Dim> T;
            T.matrix() = M;
            if constexpr (Dim == 2) {
              row.T_estimate = lift_planar(T);
            } else {
              row.T_estimate = T;
            }
          },
          dump.set);
      row.record.dataset = "maps " + std::to_string(c.query) + " -> " + std::to_string(c.match);
      row.translation_error = (row.T_estimate.translation() - T_truth.translation()).norm();
      row.rotation_error_deg = rotation_error_deg<3>(row.T_estimate, T_truth);
      row.correct = is_true && row.translation_error < config.pose_tolerance;
      run.rows.push_back(std::move(row));
      report("verify", ++solves, total_solves);
    }
  }
  run.seconds["verify_s"] = clock.ms() / 1000.0;

  // Scores, curves and the pose graphs, per solver.
  clock = StopWatch();
  const int positives = static_cast<int>(run.true_closures.size());
  std::vector<Rigid<3>> anchors_odo;
  for (const LocalMap& m : maps) anchors_odo.push_back(m.T_world_map_odometry);
  std::vector<PoseEdge> odometry_edges;
  for (int k = 0; k + 1 < n_maps; ++k) {
    PoseEdge e;
    e.from = k;
    e.to = k + 1;
    e.T_from_to = anchors_odo[k].inverse() * anchors_odo[k + 1];
    e.sigma = odometry_sigma(config.drift, e.T_from_to.translation().norm());
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
  run.ape_without = absolute_pose_error(run.odometry, run.truth);
  const double deg = M_PI / 180.0;
  for (const std::string& name : config.solvers) {
    SolverSummary sum;
    sum.solver = name;
    std::vector<const ClosureRow*> rows;
    for (const ClosureRow& r : run.rows) {
      if (r.record.solver == name) rows.push_back(&r);
    }
    sum.score = score_at(rows, positives, [](const ClosureRow& r) { return r.record.accepted; });
    int max_inliers = 0;
    bool has_p = false;
    std::vector<PoseEdge> edges = odometry_edges;
    for (const ClosureRow* r : rows) {
      sum.inliers_mean += r->record.inliers;
      sum.time_ms_mean += r->record.time_ms;
      sum.calibration_ms_mean += r->record.calibration_ms;
      max_inliers = std::max(max_inliers, r->record.inliers);
      has_p = has_p || std::isfinite(r->record.p_value);
      if (!r->record.accepted) continue;
      ++sum.accepted;
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
        sum.alpha_curve.push_back(
            {alpha, score_at(rows, positives, [alpha](const ClosureRow& r) {
               return std::isfinite(r.record.p_value) && r.record.p_value < alpha;
             })});
      }
    }
    sum.loop_edges = static_cast<int>(edges.size() - odometry_edges.size());
    PoseGraphParams gp;
    const PoseGraphResult plain = optimise_pose_graph(anchors_odo, edges, gp);
    gp.robust = true;
    const PoseGraphResult robust = optimise_pose_graph(anchors_odo, edges, gp);
    sum.poses_with = scan_poses(plain.poses);
    sum.poses_with_robust = scan_poses(robust.poses);
    sum.ape_with = absolute_pose_error(sum.poses_with, run.truth);
    sum.ape_with_robust = absolute_pose_error(sum.poses_with_robust, run.truth);
    run.summary.push_back(std::move(sum));
  }
  run.seconds["pose_graph_s"] = clock.ms() / 1000.0;
  run.seconds["total_s"] = total_clock.ms() / 1000.0;
  return run;
}

}  // namespace verifybench
