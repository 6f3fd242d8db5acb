// `verifybench loop`: loop closure on a sequence (issue #14), simulated along a trajectory or on a
// KITTI-layout folder of scans; see loop/sequence.hpp.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <iostream>
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

void add_loop_options(Options& o) {
  o.group("sequence")
      .add("trajectory", "FILE", "",
           "KITTI poses (one row-major 3x4 a line): scans are simulated along it; `block` (no "
           "such file): a 220 m x 140 m block driven twice, the data-free demo")
      .add("trajectory-frame", "F", "velodyne",
           "--trajectory's frame: velodyne, or camera (KITTI odometry's poses.txt; needs --calib)")
      .add("calib", "FILE", "", "KITTI calib.txt whose `Tr:` line maps Velodyne into camera")
      .add("sequence", "DIR", "",
           "a recorded sequence: a folder (or a CARMEN log) in one of the layouts of "
           "--sequence-format")
      .add("sequence-format", "F", "", "the layout: " + source_names() + " (default: detected)")
      .add("poses-file", "FILE", "", "folder layout: its TUM or KITTI poses file")
      .add("sensor", "NAME", "", "helipr: Ouster, Velodyne, Aeva or Avia (default: the one there)")
      .add("reference", "FILE", "",
           "ground truth when the sequence's own poses are not: a TUM or KITTI file (matched to "
           "the scans by stamp, else by index), or for carmen a corrected log")
      .add("relations", "FILE", "",
           "reference relations (Kuemmerle et al. 2009: `t1 t2 x y z roll pitch yaw` a line, e.g. "
           "radish2d's aces.relations): the report adds their relation error without and with "
           "loops; needs a sequence that logs its odometry (carmen)")
      .add("first-frame", "I", "0", "first frame of the excerpt")
      .add("last-frame", "I", "-1", "last frame of the excerpt (-1 = the end)");
  // Every stage's settings are rows declared beside the stage (core/param_rows.hpp): the options,
  // their defaults and ranges here, and the report's parameters.loop below, come from them.
  const LoopConfig defaults;
  o.group("simulated world and LiDAR (without --sequence)");
  cli::add_rows(o, lidar_param_rows(), defaults.lidar);
  cli::add_rows(o, world_param_rows(), defaults.world);
  o.group("odometry")
      .add("odometry", "drift|gicp|poses|log", "drift",
           "drift: the drift model below on the true poses; gicp: PCL GICP of each scan to the "
           "last --gicp-map-scans scans; poses: --odometry-file (e.g. KISS-ICP's output); log: "
           "the recording's own (a CARMEN log's odometry)")
      .add("odometry-file", "FILE", "",
           "poses: a TUM or KITTI file, matched to the scans by stamp, else by index");
  cli::add_rows(o, gicp_param_rows(), defaults.gicp);
  cli::add_rows(o, drift_param_rows(), defaults.drift);
  o.group("scans, maps, retrieval, ground truth, pose graph, dense check");
  cli::add_rows(o, loop_param_rows(), defaults);
  cli::add_rows(o, local_map_param_rows(), defaults.maps);
  cli::add_rows(o, retrieval_param_rows(), defaults.retrieval);
  cli::add_rows(o, dense_check_param_rows(), defaults.dense);
  o.group(
      "front end of each local map (the same options as `verifybench extract`; --max-hamming "
      "and --max-feature-distance also bound retrieval's votes)");
  cli::add_rows(o, frontend_param_rows(), loop_extract_defaults());
  cli::add_solver_options(o, {loop_solver_defaults(), "DIR",
                              "report folder: loop.json, loop.md, trajectories/ (required; new or "
                              "empty)"});
  o.add("no-plots", "", "",
        "do not draw the figures (DIR/loop_trajectory_<solver>.{png,pdf}, DIR/loop_pr.{png,pdf}; "
        "drawn by reports/plot_loop.py on /usr/bin/python3 after the run)");
  o.add("overwrite", "", "",
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

LoopConfig loop_config(const Options& o) {
  LoopConfig c;
  const bool has_trajectory = o.given("trajectory"), has_sequence = o.given("sequence");
  if (has_trajectory == has_sequence) {
    throw UsageError("give one of --trajectory FILE (simulated scans) or --sequence DIR");
  }
  Trajectory poses, odometry_poses;
  std::vector<double> stamps;
  if (has_sequence) {
    c.sequence_dir = o.text("sequence");
    SourceOptions so;
    so.poses_file = o.text("poses-file");
    so.sensor = o.text("sensor");
    const std::string format = o.text("sequence-format");
    so.reference = o.text("reference");  // carmen: a corrected log; the others ignore it
    try {
      c.source = open_sequence(c.sequence_dir, format, so);
    } catch (const std::invalid_argument& e) {
      throw UsageError(std::string("--sequence: ") + e.what());
    }
    const SequenceInfo& info = c.source->info();
    stamps = info.stamps;
    if (o.given("reference") && info.format != "carmen") {
      poses = frames_of(read_poses_file(o.text("reference")), stamps, o.text("reference"));
      c.reference = o.text("reference");
    } else if (!info.poses.empty()) {
      poses = info.poses;
      c.reference = info.poses_file;
    } else {
      throw UsageError("--sequence: " + c.sequence_dir + " (" + info.format +
                       ") carries no reference poses: give --reference FILE");
    }
    if (o.text("odometry") == "log") {
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
      c.relations_file = o.text("relations");
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
    const std::string trajectory = o.text("trajectory");
    poses = trajectory == "block" && !std::filesystem::exists(trajectory)
                ? block_laps(220.0, 140.0, 2)  // every map of the second lap revisits the first
                : read_kitti_poses(trajectory);
    std::string frame = o.text("trajectory-frame");
    if (frame == "camera") {
      if (!o.given("calib")) throw UsageError("--trajectory-frame camera needs --calib FILE");
      poses = camera_to_velodyne(poses, read_kitti_calib_tr(o.text("calib")));
    } else if (frame != "velodyne") {
      throw UsageError("--trajectory-frame: '" + frame + "' is not velodyne or camera");
    }
    c.reference = o.text("trajectory");
    if (o.text("odometry") == "log") throw UsageError("--odometry log needs a --sequence");
  }
  if (o.text("odometry") == "poses") {
    if (!o.given("odometry-file")) throw UsageError("--odometry poses needs --odometry-file FILE");
    odometry_poses =
        frames_of(read_poses_file(o.text("odometry-file")), stamps, o.text("odometry-file"));
  } else if (o.given("odometry-file")) {
    throw UsageError("--odometry-file goes with --odometry poses");
  }
  if (odometry_poses.size() != 0 && odometry_poses.size() != poses.size()) {
    throw UsageError("--odometry " + o.text("odometry") + ": " +
                     std::to_string(odometry_poses.size()) + " poses for " +
                     std::to_string(poses.size()) + " scans");
  }
  const long long n = static_cast<long long>(poses.size());
  const long long first = o.integer("first-frame", 0, n - 1);
  long long last = o.integer("last-frame", -1, n - 1);
  if (last < 0) last = n - 1;
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
  cli::read_rows(o, loop_param_rows(), c);
  cli::read_rows(o, frontend_param_rows(), c.extract);
  cli::read_rows(o, lidar_param_rows(), c.lidar);
  cli::read_rows(o, world_param_rows(), c.world);
  c.odometry = o.text("odometry");
  if (c.odometry != "drift" && c.odometry != "gicp" && c.odometry != "poses" &&
      c.odometry != "log") {
    throw UsageError("--odometry: '" + c.odometry + "' is not drift, gicp, poses or log");
  }
  cli::read_rows(o, gicp_param_rows(), c.gicp);
  cli::read_rows(o, drift_param_rows(), c.drift);
  cli::read_rows(o, local_map_param_rows(), c.maps);
  cli::read_rows(o, retrieval_param_rows(), c.retrieval);
  cli::read_rows(o, dense_check_param_rows(), c.dense);
  c.solvers = cli::solver_names(o);
  c.params = cli::solver_params(o, loop_solver_defaults());
  c.accept = cli::accept_params(o);
  c.seed = c.params.seed;
  c.threads = c.params.threads;
  c.params.threads = 1;  // maps are built in parallel; each solve on one thread
  c.extract.label_threshold = c.params.inlier_threshold;
  try {
    c.validate();
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  }
  return c;
}

nlohmann::json loop_parameters(const Options& o, const LoopConfig& c) {
  nlohmann::json p = cli::params_json(c.params, c.accept, cli::criteria(o));
  p["threads"] = c.threads;
  p["loop"] = {{"trajectory", o.text("trajectory")},
               {"sequence", c.sequence_dir},
               {"sequence_format", c.source ? c.source->info().format : ""},
               {"sequence_note", c.source ? c.source->info().note : ""},
               {"reference", c.reference},
               {"relations", c.relations_file},
               {"odometry_file", o.text("odometry-file")},
               {"trajectory_frame", o.text("trajectory-frame")},
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
  loop["dense_check"]["icp_max_iterations"] = c.dense.icp.max_iterations;
  loop["gicp"]["max_iterations"] = c.gicp.max_iterations;
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
  Options o;
  add_loop_options(o);
  if (o.parse_or_help(args,
                      "usage: verifybench loop (--trajectory FILE | --sequence DIR) "
                      "[options] --out DIR\n"))
    return 0;
  const LoopConfig config = loop_config(o);
  const std::string dir = o.required("out");
  try {
    check_loop_dir(dir, o.flag("overwrite"));
  } catch (const std::runtime_error& e) {
    throw UsageError(std::string("--out: ") + e.what());
  }
  const bool quiet = o.flag("quiet");
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
      loop_report(config, run, make_context(argv, config.seed), loop_parameters(o, config));
  const std::string md = loop_markdown(config, run);
  if (o.flag("overwrite")) clear_loop_dir(dir);
  write_loop_report(dir, report, md);
  write_loop_trajectories(dir, config, run);
  if (!o.flag("no-plots")) draw_loop_figures(dir, quiet);
  if (!quiet) std::cerr << md;
  std::cout << dir << "/loop.json\n";
  for (const ClosureRow& r : run.rows) {
    if (r.record.status == "error") {
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
