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
#include "loop/evaluation.hpp"
#include "loop/odometry.hpp"
#include "solvers/registry.hpp"

namespace verifybench {

namespace {

/// --odometry-prior: odometry's relative motion of the pair (query map -> match map, the frames of
/// T_truth) with odometry_sigma() of the travel between the two anchors; planar sets get its
/// (yaw, x, y) part.
void attach_odometry_prior(Dump& dump, const std::vector<LocalMap>& maps, const Candidate& c,
                           const DriftParams& drift) {
  const Rigid<3> T0 =
      maps[c.match].T_world_map_odometry.inverse() * maps[c.query].T_world_map_odometry;
  const Eigen::Matrix<double, 6, 1> sigma =
      odometry_sigma(drift, map_travel(maps, c.query, c.match));
  std::visit(
      [&](auto& set) {
        constexpr int Dim = std::decay_t<decltype(set.corr.source)>::RowsAtCompileTime;
        PosePrior<Dim> prior;
        if constexpr (Dim == 2) {
          prior.T_target_source = planar(T0);
          prior.covariance = Eigen::Vector3d(sigma(2), sigma(3), sigma(4)).cwiseAbs2().asDiagonal();
        } else {
          prior.T_target_source = T0;
          prior.covariance = sigma.cwiseAbs2().asDiagonal();
        }
        set.corr.prior = prior;
      },
      dump.set);
}

}  // namespace

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
  bool known_pipeline = false;
  for (const auto& info : list_pipelines()) known_pipeline |= info.name == extract.pipeline;
  if (!known_pipeline) {
    throw std::invalid_argument("loop: unknown pipeline '" + extract.pipeline + "'");
  }
  if (solvers.empty()) throw std::invalid_argument("loop: no solver");
  // The odometry kind by name (UnknownName lists the kinds), then its own fields.
  const OdometryInfo& odometry_kind = find_odometry(odometry);
  if (odometry_kind.validate) odometry_kind.validate(*this);
  if (!stamps.empty() && stamps.size() != truth.size()) {
    throw std::invalid_argument("loop: " + std::to_string(stamps.size()) + " stamps for " +
                                std::to_string(truth.size()) + " frames");
  }
  SolverRegistry::check(solvers);
  maps.validate();
  retrieval.validate();
  drift.validate();
  calibration.validate();
  if (calibration.enabled && !(source && source->info().planar)) {
    throw std::invalid_argument(
        "--odometry-calibration needs a 2D laser recording (a CARMEN log: planar scans); " +
        (source ? "the " + source->info().format + " sequence " + source->info().dir + " is not"
                : std::string("the simulated world is 3D")));
  }
  dense.validate();
  consistency.validate();
  params.validate();
  accept.validate();
  if (!source) {
    world.validate();
    lidar.validate();
  }
}

ExtractParams loop_extract_defaults() {
  ExtractParams p;
  p.matching.kind = MatchingPolicy::Kind::nearest;
  p.p2.bev.range = 80.0;
  p.max_matches = 5000;
  return p;
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
      const double d =
          (maps[q].T_world_map_truth.translation() - maps[m].T_world_map_truth.translation())
              .norm();
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

// The stages of run_loop, in its order. Each fills its part of the run and its timing.

/// The progress callback, or nothing.
struct Progress {
  const LoopProgress& progress;
  void operator()(const std::string& stage, long long done, long long total) const {
    if (progress) progress(stage, done, total);
  }
};

/// Sources: the scans used, one every scan_spacing metres of true travel (select_frames), from the
/// recorded sequence (config.source, loop/sources/) or ray-cast by the simulated LiDAR in a seeded
/// street world along the true trajectory (generators/world.hpp, generators/lidar.hpp).
struct Scans {
  std::unique_ptr<LidarSimulator> lidar;  ///< null when read
  ScanSource scan;                        ///< trajectory frame -> points, sensor frame
};

std::vector<int> scans_used(const LoopConfig& config) {
  std::vector<int> frames = select_frames(config.truth, config.scan_spacing);
  if (frames.size() < 3) {
    throw std::invalid_argument("loop: " + std::to_string(frames.size()) +
                                " scans at this spacing (at least 3)");
  }
  return frames;
}

Scans open_scans(const LoopConfig& config, LoopRun& run) {
  StopWatch clock;
  Scans scans;
  if (!config.source) {
    WorldParams wp = config.world;
    wp.seed = derive_seed(config.seed, {1});
    const World world = build_street_world(config.truth, wp);
    run.world = world.counts;
    scans.lidar = std::make_unique<LidarSimulator>(world.mesh);
  }
  run.seconds["world_s"] = clock.ms() / 1000.0;
  const LidarSimulator* lidar = scans.lidar.get();
  scans.scan = [lidar, &config](int frame) -> std::vector<Eigen::Vector3f> {
    if (lidar) {
      return lidar->scan(config.truth[frame], config.lidar,
                         derive_seed(config.seed, {2, static_cast<std::uint64_t>(frame)}));
    }
    return config.source->points(config.first_frame + frame);
  };
  return scans;
}

/// Odometry: the kind config.odometry names (loop/odometry.hpp: drift, gicp, poses, log), for
/// every frame, then its calibration from the scans when on (loop/odometry_calibration.hpp); run.truth
/// and run.odometry keep the frames used.
Trajectory run_odometry(const LoopConfig& config, const ScanSource& scans, const Progress& report,
                        LoopRun& run) {
  StopWatch clock;
  const OdometryInfo& kind = find_odometry(config.odometry);
  Trajectory odometry_all =
      kind.run({config, run.frames, scans,
                [&](long long done, long long total) { report("odometry", done, total); }});
  run.drift = config.drift;
  if (config.calibration.enabled) {
    run.calibration = calibrate_odometry(run.frames, scans, config.calibration, odometry_all);
    run.drift.yaw_deg = std::max(run.calibration.yaw_sigma_deg_per_sqrt_m, 1e-3);
  }
  for (int f : run.frames) {
    run.truth.push_back(config.truth[f]);
    run.odometry.push_back(odometry_all[f]);
  }
  run.seconds["odometry_s"] = clock.ms() / 1000.0;
  return odometry_all;
}

/// Local maps (loop/local_maps.hpp: every map_length metres of odometry travel, in the frame of
/// their middle scan) and the front end's features of each (frontend/extract.hpp: 3d ISS + B-SHOT,
/// 2d BEV + ORB, ...), in parallel over maps (each map's work is its own); run.maps describes them.
struct MapsAndFeatures {
  std::vector<LocalMap> maps;
  std::vector<Features> features;
};

MapsAndFeatures build_maps(const LoopConfig& config, const Trajectory& odometry_all,
                           const ScanSource& scans, const Progress& report, LoopRun& run) {
  StopWatch clock;
  const auto groups = partition_maps(odometry_all, run.frames, config.maps.map_length);
  const int n_maps = static_cast<int>(groups.size());
  MapsAndFeatures out;
  out.maps.resize(n_maps);
  out.features.resize(n_maps);
  std::vector<double> feature_ms(n_maps, 0.0), map_ms(n_maps, 0.0);
  {
    WorkerPool pool(config.threads);
    std::mutex mutex;
    long long done = 0;
    pool.parallel_for(n_maps, [&](int k) {
      StopWatch c;
      out.maps[k] = build_local_map(k, groups[k], odometry_all, config.truth, scans, config.maps);
      map_ms[k] = c.ms();
      c = StopWatch();
      out.features[k] = extract_features(out.maps[k].points, config.extract);
      feature_ms[k] = c.ms();
      std::lock_guard<std::mutex> lock(mutex);
      report("maps", ++done, n_maps);
    });
  }
  run.seconds["maps_s"] = std::accumulate(map_ms.begin(), map_ms.end(), 0.0) / 1000.0;
  run.seconds["features_s"] = std::accumulate(feature_ms.begin(), feature_ms.end(), 0.0) / 1000.0;
  run.seconds["maps_wall_s"] = clock.ms() / 1000.0;
  for (const LocalMap& m : out.maps) {
    MapInfo info;
    info.index = m.index;
    info.first_frame = m.frames.front();
    info.last_frame = m.frames.back();
    info.anchor = m.anchor;
    info.scans = static_cast<int>(m.frames.size());
    info.points = static_cast<int>(m.points.size());
    info.keypoints = static_cast<int>(out.features[m.index].points.size());
    info.occupied_cells = static_cast<int>(m.occupancy.size());
    info.position_truth = m.T_world_map_truth.translation();
    run.maps.push_back(info);
  }
  return out;
}

/// Ground truth (true_closures: pairs at least min_map_gap apart, true anchors within
/// gt_max_distance, occupancies overlapping by more than gt_overlap), then retrieval
/// (loop/retrieval.hpp: the candidate pairs, by the registry's retriever).
void truth_and_retrieval(const LoopConfig& config, const MapsAndFeatures& mf, LoopRun& run) {
  StopWatch clock;
  run.true_closures = true_closures(mf.maps, config.retrieval.min_map_gap, config.gt_max_distance,
                                    config.gt_overlap);
  RetrievalParams rp = config.retrieval;
  rp.max_hamming = config.extract.max_hamming;
  rp.max_feature_distance = config.extract.max_feature_distance;
  run.candidates = retrieve_candidates(mf.features, rp);
  run.seconds["retrieval_s"] = clock.ms() / 1000.0;
}

/// Verification, one pair: the matcher's correspondences of its features (seeded by the pair), the
/// ground truth marked on them, and odometry's prior when --odometry-prior.
Dump pair_correspondences(const LoopConfig& config, const DriftParams& drift,
                          const MapsAndFeatures& mf, const Candidate& c,
                          const Rigid<3>& T_truth) {
  ExtractParams ep = config.extract;
  ep.seed = derive_seed(
      config.seed, {4, static_cast<std::uint64_t>(c.query), static_cast<std::uint64_t>(c.match)});
  Dump dump = match_features(mf.features[c.query], mf.features[c.match], T_truth, ep);
  if (config.odometry_prior) attach_odometry_prior(dump, mf.maps, c, drift);
  return dump;
}

/// Verification, one solver on one pair's correspondences: the harness's row (verify, then
/// trial_record) and the solver's motion lifted to SE(3); no correspondence is a rejection.
void solve_pair(Solver& solver, const std::string& name, Dump& dump, bool is_true,
                const SolverParams& sp, const AcceptParams& accept, ClosureRow& row) {
  std::visit(
      [&](auto& set) {
        constexpr int Dim = std::decay_t<decltype(set.corr.source)>::RowsAtCompileTime;
        set.truth.positive = is_true;
        if (set.corr.empty()) {
          row.record.solver = name;
          row.record.dim = Dim;
          row.record.status = Status::rejected;
          row.record.message = "no correspondence";
          return;
        }
        const Verification<Dim> v = verify(solver, set.corr, sp, accept);
        row.record = trial_record(v, name, set, sp, SuccessCriteria{});
        if constexpr (Dim == 2) {
          row.T_estimate = lift_planar(v.result.T_target_source);
        } else {
          row.T_estimate = v.result.T_target_source;
        }
      },
      dump.set);
}

/// Verification, after the accept rule: the dense check (acceptance/dense_check.hpp, when on) of a
/// pair the rule accepted may overrule it (a rejected pair is not refined: its ICP would cost a
/// map registration per solver and candidate and decide nothing); the solver's errors against the
/// truth; the motion the loop goes on with; and whether the closure is correct (a true closure
/// within pose_tolerance).
void judge_row(const LoopConfig& config, const LocalMap& q, const LocalMap& m, bool is_true,
               ClosureRow& row) {
  row.rule_accepted = row.record.accepted;
  const double min_overlap = config.dense.min_overlap_for(config.accept.rule);
  if (min_overlap > 0.0 && row.record.accepted && !row.record.T_target_source.empty()) {
    row.dense = dense_check(q.points, m.points, row.T_estimate, config.dense);
    if (!(row.dense.overlap > min_overlap)) {
      row.record.accepted = false;
      if (row.record.status == Status::ok) row.record.status = Status::rejected;  // as run's rows
      row.record.message = "dense check: overlap " + std::to_string(row.dense.overlap) +
                           " after ICP, not above " + std::to_string(min_overlap);
    }
  }
  row.translation_error = (row.T_estimate.translation() - row.T_truth.translation()).norm();
  row.rotation_error_deg = rotation_error_deg<3>(row.T_estimate, row.T_truth);
  if (row.dense.ran) {
    // The loop goes on with the refined motion (as KISS-SLAM does): it is the one judged and
    // put in the pose graph; the solver's own errors stay in the row.
    row.T_solver = row.T_estimate;
    row.T_estimate = row.dense.icp.T_target_source;
  }
  const double loop_error = (row.T_estimate.translation() - row.T_truth.translation()).norm();
  row.correct = is_true && loop_error < config.pose_tolerance;
}

/// Verification: every solver of the registry on every candidate pair (seeded by the pair), one
/// ClosureRow each, in candidate then solver order.
void verify_candidates(const LoopConfig& config, const MapsAndFeatures& mf, const Progress& report,
                       LoopRun& run) {
  StopWatch clock;
  std::vector<std::unique_ptr<Solver>> solvers;
  for (const auto& name : config.solvers) solvers.push_back(SolverRegistry::create(name));
  // The maps are known: where their dense check runs, the runner-up test is off unless asked.
  AcceptParams accept = config.accept;
  accept.resolve_runner_up(config.dense.min_overlap_for(accept.rule) > 0.0);
  const long long total_solves =
      static_cast<long long>(run.candidates.size()) * static_cast<long long>(solvers.size());
  long long solves = 0;
  for (const Candidate& c : run.candidates) {
    const LocalMap& q = mf.maps[c.query];
    const LocalMap& m = mf.maps[c.match];
    const Rigid<3> T_truth = m.T_world_map_truth.inverse() * q.T_world_map_truth;
    Dump dump = pair_correspondences(config, run.drift, mf, c, T_truth);
    const double overlap = overlap_ratio(q.occupancy, m.occupancy);
    bool is_true = false;
    for (const TrueClosure& t : run.true_closures) {
      if (t.query == c.query && t.match == c.match) is_true = true;
    }
    SolverParams sp = config.params;
    sp.seed = derive_seed(
        config.seed, {5, static_cast<std::uint64_t>(c.query), static_cast<std::uint64_t>(c.match)});
    for (std::size_t s = 0; s < solvers.size(); ++s) {
      ClosureRow row;
      row.query = c.query;
      row.match = c.match;
      row.votes = c.votes;
      row.overlap = overlap;
      row.true_closure = is_true;
      row.T_truth = T_truth;
      solve_pair(*solvers[s], config.solvers[s], dump, is_true, sp, accept, row);
      row.record.dataset = "maps " + std::to_string(c.query) + " -> " + std::to_string(c.match);
      judge_row(config, q, m, is_true, row);
      run.rows.push_back(std::move(row));
      report("verify", ++solves, total_solves);
    }
  }
  run.seconds["verify_s"] = clock.ms() / 1000.0;
}

/// Verification across closures (loop/consistency.hpp, when on): per solver, the accepted closures
/// outside the largest set that pairwise agree through the odometry are rejected.
void check_consistency(const LoopConfig& config, const MapsAndFeatures& mf, LoopRun& run) {
  if (config.consistency.confidence <= 0.0) return;
  StopWatch clock;
  for (const std::string& solver : config.solvers) {
    std::vector<ClosureRow*> accepted;
    for (ClosureRow& row : run.rows) {
      if (row.record.solver == solver && row.record.accepted) accepted.push_back(&row);
    }
    if (accepted.empty()) continue;
    std::vector<LoopMeasurement> loops;
    for (const ClosureRow* row : accepted) {
      loops.push_back({row->query, row->match, row->T_estimate});
    }
    const ConsistencyModel model{run.drift, config.loop_sigma_trans, config.loop_sigma_rot_deg,
                                 accepted.front()->record.dim};
    const ConsistentSet set = consistent_set(loops, mf.maps, model, config.consistency,
                                             config.params.time_limit_s);
    const std::vector<int>& kept = set.kept;
    for (std::size_t k = 0; k < accepted.size(); ++k) {
      ClosureRow& row = *accepted[k];
      row.consistent = std::binary_search(kept.begin(), kept.end(), static_cast<int>(k));
      if (!*row.consistent) {
        row.record.accepted = false;
        row.record.message = "loop consistency: outside the largest consistent set (" +
                             std::to_string(kept.size()) + " of " +
                             std::to_string(accepted.size()) + " closures" +
                             (set.proven ? ")" : "; the time limit cut the search: its best set)");
      }
    }
  }
  run.seconds["consistency_s"] = clock.ms() / 1000.0;
}

/// Metrics of the decisions, back end and metrics of the trajectories, per solver
/// (loop/evaluation.hpp): scores and curves; the pose graph with the accepted closures by each
/// back end (loop/backend.hpp: plain, robust); the APE of every scan with and without loops.
void back_end_and_metrics(const LoopConfig& config, const MapsAndFeatures& mf, LoopRun& run) {
  StopWatch clock;
  score_solvers(config, run);
  optimise_pose_graphs(config, mf.maps, run);
  trajectory_errors(config, run);
  run.seconds["pose_graph_s"] = clock.ms() / 1000.0;
}

}  // namespace

// The loop as its stages (sequence.hpp's header; the report is loop/loop_report.hpp's, written by
// the command from the run).
LoopRun run_loop(const LoopConfig& config, const LoopProgress& progress) {
  config.validate();
  const Progress report{progress};
  StopWatch total_clock;
  LoopRun run;
  // Sources: the scans used, simulated or read.
  run.frames = scans_used(config);
  const Scans scans = open_scans(config, run);
  // Odometry: the registry's kind (drift, gicp, poses, log).
  const Trajectory odometry_all = run_odometry(config, scans.scan, report, run);
  // Local maps and the front end's features of each.
  const MapsAndFeatures mf = build_maps(config, odometry_all, scans.scan, report, run);
  // Ground truth and retrieval: the true closures and the candidate pairs.
  truth_and_retrieval(config, mf, run);
  // Verification: every solver on every candidate, then the dense check.
  verify_candidates(config, mf, report, run);
  // Verification across closures: the largest pairwise-consistent set (when on).
  check_consistency(config, mf, run);
  // Metrics and back end: scores, pose graphs (plain, robust), APE.
  back_end_and_metrics(config, mf, run);
  run.seconds["total_s"] = total_clock.ms() / 1000.0;
  return run;
}

const std::vector<ParamRow<LoopConfig>>& loop_param_rows() {
  using P = LoopConfig;
  static const std::vector<ParamRow<P>> rows = {
      field_row(&P::scan_spacing, "scan-spacing", "scan_spacing_m", "M",
                "use a scan every M metres of travel", 1e-3, 1e6, "a value in [0.001, 1e6]"),
      field_row(&P::gt_overlap, "gt-overlap", "gt_overlap", "F",
                "true closure: occupancy overlap above F of the smaller map", 1e-6, 1.0,
                "a value in (0, 1]"),
      field_row(&P::gt_max_distance, "gt-max-distance", "gt_max_distance_m", "M",
                "true closure: anchors closer than M", 1e-6, 1e9, "a value > 0"),
      field_row(&P::pose_tolerance, "pose-tolerance", "pose_tolerance_m", "M",
                "correct closure: relative translation error under M", 1e-6, 1e9, "a value > 0"),
      field_row(&P::loop_sigma_trans, "loop-sigma-trans", "loop_sigma_trans_m", "M",
                "pose graph: loop edge translation sigma", 1e-6, 1e6, "a value > 0"),
      field_row(&P::loop_sigma_rot_deg, "loop-sigma-rot-deg", "loop_sigma_rot_deg", "DEG",
                "pose graph: loop edge rotation sigma", 1e-6, 180.0, "a value in (0, 180]"),
      field_row(&P::odometry_prior, "odometry-prior", "odometry_prior", "",
                "each candidate carries odometry's motion as a pose prior (drift-model sigmas of "
                "the travel between the maps): the pvalue rule's --prior-gate and jcbb's prior "
                "mode use it")};
  return rows;
}

}  // namespace verifybench
