// `verifybench loop`: loop closure on a sequence (issue #14), simulated along a trajectory or on a
// KITTI-layout folder of scans; see loop/sequence.hpp.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <limits>
#include <sstream>
#include <cstring>
#include <fcntl.h>

#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include "apps/cli.hpp"
#ifdef VERIFYBENCH_HAVE_LOOP
#include "apps/param_options.hpp"
#include "frontend/params.hpp"
#include "generators/world.hpp"
#include "harness/progress.hpp"
#include "loop/loop_report.hpp"
#include "loop/odometry.hpp"
#endif

namespace verifybench {

#ifdef VERIFYBENCH_HAVE_LOOP
namespace {

std::string source_names() {
  std::string names;
  for (const auto& info : list_sources()) names += (names.empty() ? "" : ", ") + info.name;
  return names;
}

/// The paper's outdoor setting: eps 1 m (its maps are 100 m at 0.5 m voxels).
SolverParams loop_solver_defaults() {
  SolverParams p;
  p.eps = 1.0;
  return p;
}

/// The command line's own settings (the stages' settings are rows bound to LoopConfig).
struct LoopLine {
  std::string trajectory, trajectory_frame = "velodyne", calib, sequence, sequence_format,
      poses_file, sensor, reference, relations, odometry_file;
  long long first_frame = 0, last_frame = -1;
  bool no_plots = false, overwrite = false;
};

void add_loop_options(Options& o, LoopLine& l, LoopConfig& c, cli::SolverOptions& s) {
  o.group("sequence")
      .text("trajectory", l.trajectory, "FILE",
            "KITTI poses (one row-major 3x4 a line): scans are simulated along it; `block` (no "
            "such file): a 220 m x 140 m block driven twice, the data-free demo")
      .bind("trajectory-frame", "F", l.trajectory_frame,
            "--trajectory's frame: velodyne, or camera (KITTI odometry's poses.txt; needs --calib)",
            [&l](const std::string& v) {
              if (v != "velodyne" && v != "camera") {
                throw UsageError("--trajectory-frame: '" + v + "' is not velodyne or camera");
              }
              l.trajectory_frame = v;
            })
      .text("calib", l.calib, "FILE", "KITTI calib.txt whose `Tr:` line maps Velodyne into camera")
      .text("sequence", l.sequence, "DIR",
            "a recorded sequence: a folder (or a CARMEN log) in one of the layouts of "
            "--sequence-format")
      .text("sequence-format", l.sequence_format, "F",
            "the layout: " + source_names() + " (default: detected)")
      .text("poses-file", l.poses_file, "FILE", "folder layout: its TUM or KITTI poses file")
      .text("sensor", l.sensor, "NAME",
            "helipr: Ouster, Velodyne, Aeva or Avia (default: the one there)")
      .text("reference", l.reference, "FILE",
            "ground truth when the sequence's own poses are not: a TUM or KITTI file (matched to "
            "the scans by stamp, else by index), or for carmen a corrected log")
      .text("relations", l.relations, "FILE",
            "reference relations (Kuemmerle et al. 2009: `t1 t2 x y z roll pitch yaw` a line, "
            "e.g. radish2d's aces.relations): the report adds their relation error without and "
            "with loops; needs a sequence that logs its odometry (carmen)")
      .integer("first-frame", l.first_frame, "I", "first frame of the excerpt", 0,
               std::numeric_limits<int>::max())
      .integer("last-frame", l.last_frame, "I", "last frame of the excerpt (-1 = the end)", -1,
               std::numeric_limits<int>::max());
  // Every stage's settings are rows declared beside the stage (core/param_rows.hpp), bound here to
  // the LoopConfig the run reads; the report's parameters.loop below comes from the same rows.
  o.group("simulated world and LiDAR (without --sequence)");
  cli::add_rows(o, lidar_param_rows(), c.lidar);
  cli::add_rows(o, world_param_rows(), c.world);
  o.group("odometry")
      .bind("odometry", "drift|gicp|poses|log", c.odometry,
            "drift: the drift model below on the true poses; gicp: PCL GICP of each scan to the "
            "last --gicp-map-scans scans; poses: --odometry-file (e.g. KISS-ICP's output); log: "
            "the recording's own (a CARMEN log's odometry)",
            [&c](const std::string& v) {
              if (v != "drift" && v != "gicp" && v != "poses" && v != "log") {
                throw UsageError("--odometry: '" + v + "' is not drift, gicp, poses or log");
              }
              c.odometry = v;
            })
      .text("odometry-file", l.odometry_file, "FILE",
            "poses: a TUM or KITTI file, matched to the scans by stamp, else by index");
  cli::add_rows(o, gicp_param_rows(), c.gicp);
  cli::add_rows(o, drift_param_rows(), c.drift);
  cli::add_rows(o, odometry_calibration_param_rows(), c.calibration);
  o.group("scans, maps, retrieval, ground truth, pose graph, dense check, loop consistency");
  cli::add_rows(o, loop_param_rows(), c);
  cli::add_rows(o, local_map_param_rows(), c.maps);
  cli::add_rows(o, retrieval_param_rows(), c.retrieval);
  cli::add_rows(o, dense_check_param_rows(), c.dense);
  cli::add_rows(o, consistency_param_rows(), c.consistency);
  o.group(
      "front end of each local map (the same options as `verifybench extract`; --max-hamming "
      "and --max-feature-distance also bound retrieval's votes)");
  cli::add_rows(o, frontend_param_rows(), c.extract);
  cli::add_solver_options(o, s);
  o.flag("no-plots", l.no_plots,
         "do not draw the figures (DIR/loop_trajectory_<solver>.{png,pdf}, DIR/loop_pr.{png,pdf}; "
         "drawn by reports/plot_loop.py on /usr/bin/python3 after the run)");
  o.flag("overwrite", l.overwrite,
         "--out may be an earlier run's folder: it is emptied once this run is done, before its "
         "results are written");
}

/// A poses file's poses, one per scan: by nearest stamp (within 0.05 s) where the file has stamps
/// that fall in the scans' span, else by index (equal counts).
Trajectory frames_of(const StampedTrajectory& file, const std::vector<double>& stamps,
                     const std::string& path) {
  const bool by_stamp = !file.stamps.empty() && !stamps.empty() &&
                        file.stamps.front() <= stamps.back() + 0.05 &&
                        stamps.front() <= file.stamps.back() + 0.05;
  if (!by_stamp) {
    if (!stamps.empty() && file.poses.size() != stamps.size()) {
      input_error(path, 0,
                  std::to_string(file.poses.size()) + " poses for " +
                      std::to_string(stamps.size()) + " scans (no stamps to match them by)");
    }
    return file.poses;
  }
  Trajectory out;
  for (std::size_t i = 0; i < stamps.size(); ++i) {
    const auto it = std::lower_bound(file.stamps.begin(), file.stamps.end(), stamps[i]);
    std::size_t best = it == file.stamps.end() ? file.stamps.size() - 1
                                               : static_cast<std::size_t>(it - file.stamps.begin());
    if (best > 0 &&
        std::abs(file.stamps[best - 1] - stamps[i]) < std::abs(file.stamps[best] - stamps[i])) {
      --best;
    }
    if (std::abs(file.stamps[best] - stamps[i]) > 0.05) {
      std::ostringstream msg;
      msg << std::setprecision(17) << "no pose within 0.05 s of scan " << i << " (stamp "
          << stamps[i] << ")";
      input_error(path, 0, msg.str());
    }
    out.push_back(file.poses[best]);
  }
  return out;
}

/// The rest of the configuration, once the line is parsed into `l`, `c` and `s`: the sequence or
/// the simulated trajectory, the reference, the odometry poses, the excerpt; then validated.
void loop_config(const Options& o, const LoopLine& l, LoopConfig& c, cli::SolverOptions& s) {
  cli::check_solver_options(s);
  const bool has_trajectory = o.given("trajectory"), has_sequence = o.given("sequence");
  if (has_trajectory == has_sequence) {
    throw UsageError("give one of --trajectory FILE (simulated scans) or --sequence DIR");
  }
  Trajectory poses, odometry_poses;
  std::vector<double> stamps;
  if (has_sequence) {
    c.sequence_dir = l.sequence;
    SourceOptions so;
    so.poses_file = l.poses_file;
    so.sensor = l.sensor;
    const std::string& format = l.sequence_format;
    so.reference = l.reference;  // carmen: a corrected log; the others ignore it
    try {
      c.source = open_sequence(c.sequence_dir, format, so);
    } catch (const std::invalid_argument& e) {
      throw UsageError(std::string("--sequence: ") + e.what());
    }
    const SequenceInfo& info = c.source->info();
    stamps = info.stamps;
    if (o.given("reference") && info.format != "carmen") {
      poses = frames_of(read_poses_file(l.reference), stamps, l.reference);
      c.reference = l.reference;
    } else if (!info.poses.empty()) {
      poses = info.poses;
      c.reference = info.poses_file;
    } else {
      throw UsageError("--sequence: " + c.sequence_dir + " (" + info.format +
                       ") carries no reference poses: give --reference FILE");
    }
    if (c.odometry == "log") {
      if (info.odometry.empty()) {
        throw UsageError("--odometry log: " + c.sequence_dir + " (" + info.format +
                         ") logs no odometry");
      }
      odometry_poses = info.odometry;
    }
    if (o.given("relations")) {
      if (info.odometry_stream.empty()) {
        throw UsageError("--relations: " + c.sequence_dir + " (" + info.format +
                         ") logs no odometry to carry the estimate between frames");
      }
      c.relations_file = l.relations;
      c.relations = read_relations(c.relations_file);
      c.odometry_stream_stamps = info.odometry_stream_stamps;
      c.odometry_stream = info.odometry_stream;
    }
  } else {
    if (o.given("reference") || o.given("sequence-format") || o.given("poses-file") ||
        o.given("relations")) {
      throw UsageError(
          "--reference, --sequence-format, --poses-file and --relations go with --sequence");
    }
    const std::string trajectory = l.trajectory;
    poses = trajectory == "block" && !std::filesystem::exists(trajectory)
                ? block_laps(220.0, 140.0, 2)  // every map of the second lap revisits the first
                : read_kitti_poses(trajectory);
    if (l.trajectory_frame == "camera") {
      if (!o.given("calib")) throw UsageError("--trajectory-frame camera needs --calib FILE");
      poses = camera_to_velodyne(poses, read_kitti_calib_tr(l.calib));
    }
    c.reference = l.trajectory;
    if (c.odometry == "log") throw UsageError("--odometry log needs a --sequence");
  }
  if (c.odometry == "poses") {
    if (!o.given("odometry-file")) throw UsageError("--odometry poses needs --odometry-file FILE");
    odometry_poses =
        frames_of(read_poses_file(l.odometry_file), stamps, l.odometry_file);
  } else if (o.given("odometry-file")) {
    throw UsageError("--odometry-file goes with --odometry poses");
  }
  if (odometry_poses.size() != 0 && odometry_poses.size() != poses.size()) {
    throw UsageError("--odometry " + c.odometry + ": " +
                     std::to_string(odometry_poses.size()) + " poses for " +
                     std::to_string(poses.size()) + " scans");
  }
  const long long n = static_cast<long long>(poses.size());
  const long long first = l.first_frame;
  const long long last = l.last_frame < 0 ? n - 1 : l.last_frame;
  if (first > n - 1) {
    throw UsageError("--first-frame: '" + std::to_string(first) + "' is outside [0, " +
                     std::to_string(n - 1) + "]");
  }
  if (last > n - 1) {
    throw UsageError("--last-frame: '" + std::to_string(last) + "' is outside [-1, " +
                     std::to_string(n - 1) + "]");
  }
  if (last <= first) {
    throw UsageError("--last-frame " + std::to_string(last) + " is not after --first-frame " +
                     std::to_string(first));
  }
  c.truth.assign(poses.begin() + first, poses.begin() + last + 1);
  if (!odometry_poses.empty()) {
    c.odometry_poses.assign(odometry_poses.begin() + first, odometry_poses.begin() + last + 1);
  }
  if (!stamps.empty()) c.stamps.assign(stamps.begin() + first, stamps.begin() + last + 1);
  c.first_frame = static_cast<int>(first);
  c.solvers = s.solvers;
  c.params = s.params;
  c.accept = s.accept;
  c.seed = c.params.seed;
  c.threads = c.params.threads;
  c.params.threads = 1;  // maps are built in parallel; each solve on one thread
  c.extract.label_threshold = c.params.inlier_threshold;
  // The report's parameters hold the dense check's threshold in force, not "the rule's default".
  if (c.dense.min_overlap == DenseCheckParams::kRuleDefault) {
    c.dense.min_overlap = c.dense.min_overlap_for(c.accept.rule);
  }
  // The maps are known: where their dense check runs it decides, and the runner-up test is off
  // unless asked (BENCHMARK.md section 38: with both, balm's true closures have rivals too).
  c.accept.resolve_runner_up(c.dense.min_overlap > 0.0);
  try {
    c.validate();
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  }
}

nlohmann::json loop_parameters(const LoopLine& l, const LoopConfig& c,
                               const SuccessCriteria& criteria) {
  nlohmann::json p = cli::params_json(c.params, c.accept, criteria);
  p["threads"] = c.threads;
  p["loop"] = {{"trajectory", l.trajectory},
               {"sequence", c.sequence_dir},
               {"sequence_format", c.source ? c.source->info().format : ""},
               {"sequence_note", c.source ? c.source->info().note : ""},
               {"reference", c.reference},
               {"relations", c.relations_file},
               {"odometry_file", l.odometry_file},
               {"trajectory_frame", l.trajectory_frame},
               {"first_frame", c.first_frame},
               {"frames", c.truth.size()},
               {"frontend", cli::rows_json(frontend_param_rows(), c.extract)},
               {"occupancy_voxel_m", c.maps.occupancy_voxel},
               {"dense_check", cli::rows_json(dense_check_param_rows(), c.dense)},
               {"odometry", c.odometry},
               {"gicp", cli::rows_json(gicp_param_rows(), c.gicp)},
               {"drift", cli::rows_json(drift_param_rows(), c.drift)},
               {"solvers", c.solvers}};
  // The rows' values by key, then the fixed settings no option changes.
  nlohmann::json& loop = p["loop"];
  loop.update(cli::rows_json(loop_param_rows(), c));
  loop.update(cli::rows_json(local_map_param_rows(), c.maps));
  loop.update(cli::rows_json(retrieval_param_rows(), c.retrieval));
  loop.update(cli::rows_json(consistency_param_rows(), c.consistency));
  loop.update(cli::rows_json(odometry_calibration_param_rows(), c.calibration));
  loop["dense_check"]["icp_max_iterations"] = c.dense.icp.max_iterations;
  loop["gicp"]["max_iterations"] = c.gicp.max_iterations;
  loop["calibration_max_iterations"] = c.calibration.max_iterations;
  if (!c.source) {
    loop["lidar"] = cli::rows_json(lidar_param_rows(), c.lidar);
    loop["lidar"].update({{"fov_up_deg", c.lidar.fov_up_deg},
                          {"fov_down_deg", c.lidar.fov_down_deg},
                          {"min_range_m", c.lidar.min_range}});
    loop["world"] = cli::rows_json(world_param_rows(), c.world);
    loop["world"].update({{"road_half_width_m", c.world.road_half_width},
                          {"kerb_band_m", c.world.kerb_band},
                          {"building_setback_m", c.world.building_setback},
                          {"building_depth_m", c.world.building_depth},
                          {"sensor_height_m", c.world.sensor_height}});
  }
  return p;
}

/// reports/plot_loop.py for this binary: installed (PREFIX/bin/verifybench ->
/// PREFIX/share/verifybench/reports), else the source tree it was built from; "" when neither.
std::string plot_loop_script() {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    const fs::path installed = exe.parent_path() / ".." / "share" / "verifybench" / "reports" /
                               "plot_loop.py";
    if (fs::exists(installed)) return installed.string();
  }
  const fs::path source = fs::path(VERIFYBENCH_SOURCE_REPORTS) / "plot_loop.py";
  return fs::exists(source) ? source.string() : std::string();
}

/// The loop's figures (trajectories with their closures, precision-recall; PNG and PDF) in DIR,
/// by reports/plot_loop.py on Debian's /usr/bin/python3 (it has matplotlib). The run's results
/// stand without them: a missing script or interpreter, or a failed plot, is a warning that says
/// how to draw them later, not an error.
void draw_loop_figures(const std::string& dir, bool quiet) {
  const std::string script = plot_loop_script();
  const std::string python = "/usr/bin/python3";
  const auto warn = [&](const std::string& why) {
    std::cerr << "verifybench: warning: the loop figures were not drawn (" << why
              << "); draw them with reports/plot_loop.py " << dir << "\n";
  };
  if (script.empty()) return warn("reports/plot_loop.py not found");
  if (::access(python.c_str(), X_OK) != 0) return warn(python + " not found");
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  // Its stdout (the paths it wrote) stays off ours, which carries only loop.json's path.
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
  if (quiet) posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, "/dev/null", O_WRONLY, 0);
  std::vector<std::string> args{python, script, dir};
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  pid_t pid = 0;
  const int spawned = posix_spawn(&pid, python.c_str(), &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (spawned != 0) return warn(std::string("cannot start ") + python + ": " + std::strerror(spawned));
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) warn(script + " failed");
}

}  // namespace

int cmd_loop(const std::vector<std::string>& args, const std::vector<std::string>& argv) {
  LoopLine line;
  LoopConfig config;
  cli::SolverOptions s;
  s.params = loop_solver_defaults();
  s.out_value = "DIR";
  s.out_help = "report folder: loop.json, loop.md, trajectories/ (required; new or empty)";
  Options o;
  add_loop_options(o, line, config, s);
  if (o.parse_or_help(args,
                      "usage: verifybench loop (--trajectory FILE | --sequence DIR) "
                      "[options] --out DIR\n"))
    return 0;
  loop_config(o, line, config, s);
  o.require("out");
  const std::string dir = s.out;
  try {
    check_loop_dir(dir, line.overwrite);
  } catch (const std::runtime_error& e) {
    throw UsageError(std::string("--out: ") + e.what());
  }
  const bool quiet = s.quiet;
  std::unique_ptr<Progress> bar;
  std::string stage;
  // One progress line per stage (scans and maps, verification, ...), each with its own ETA.
  const LoopRun run = run_loop(config, [&](const std::string& s, long long, long long total) {
    if (quiet) return;
    if (s != stage) {
      stage = s;
      bar = std::make_unique<Progress>("loop " + s, total, true);
    }
    bar->advance(1);
  });
  bar.reset();
  const nlohmann::json report =
      loop_report(config, run, make_context(argv, config.seed), loop_parameters(line, config, s.criteria));
  const std::string md = loop_markdown(config, run);
  if (line.overwrite) clear_loop_dir(dir);
  write_loop_report(dir, report, md);
  write_loop_trajectories(dir, config, run);
  if (!line.no_plots) draw_loop_figures(dir, quiet);
  if (!quiet) std::cerr << md;
  std::cout << dir << "/loop.json\n";
  for (const ClosureRow& r : run.rows) {
    if (r.record.status == Status::error) {
      std::cerr << "verifybench: error: solver " << r.record.solver << " failed on maps " << r.query
                << " -> " << r.match << ": " << r.record.message << "\n";
      return 1;
    }
  }
  return 0;
}

#else

int cmd_loop(const std::vector<std::string>&, const std::vector<std::string>&) {
  throw UsageError("this verifybench was built without the loop stage (needs PCL, OpenCV, Ceres)");
}

#endif

}  // namespace verifybench
