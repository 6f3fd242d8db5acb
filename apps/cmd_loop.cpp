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
      .add("last-frame", "I", "-1", "last frame of the excerpt (-1 = the end)")
      .add("scan-spacing", "M", "2", "use a scan every M metres of travel");
  o.group("simulated world and LiDAR (without --sequence)")
      .add("lidar-beams", "K", "64", "beams, evenly from +2 to -24.8 deg")
      .add("lidar-columns", "K", "1024", "azimuth steps a sweep")
      .add("lidar-max-range", "M", "80", "farthest return")
      .add("lidar-noise", "M", "0.02", "range noise sigma")
      .add("lidar-dropout", "P", "0.05", "probability of a lost return")
      .add("world-building-density", "P", "0.2", "chance of a building in a block cell")
      .add("world-kerb-density", "P", "0.45",
           "chance of a pole, tree, car or clutter in a kerb cell");
  o.group("odometry")
      .add("odometry", "drift|gicp|poses|log", "drift",
           "drift: the drift model below on the true poses; gicp: PCL GICP of each scan to the "
           "last --gicp-map-scans scans; poses: --odometry-file (e.g. KISS-ICP's output); log: "
           "the recording's own (a CARMEN log's odometry)")
      .add("odometry-file", "FILE", "",
           "poses: a TUM or KITTI file, matched to the scans by "
           "stamp, else by index")
      .add("gicp-map-scans", "K", "1", "gicp: scans in the local map (1 = scan to scan)")
      .add("gicp-voxel", "M", "1", "gicp: scans downsampled to this voxel")
      .add("gicp-max-distance", "M", "1", "gicp: correspondence distance")
      .add("drift-trans", "F", "0.01", "translation sigma per metre of step")
      .add("drift-yaw-deg", "DEG", "0.05", "yaw random walk [deg / sqrt(m)]")
      .add("drift-tilt-deg", "DEG", "0.005", "roll and pitch random walk [deg / sqrt(m)]");
  o.group("maps, retrieval and ground truth")
      .add("map-length", "M", "100", "odometry travel per local map")
      .add("map-voxel", "M", "0.5", "local map voxel")
      .add("min-map-gap", "K", "3", "maps fewer than K apart are not compared")
      .add("candidates", "K", "2", "maps verified per query (most HBST votes)")
      .add("min-votes", "K", "5", "fewer votes: not a candidate")
      .add("retrieval", "KIND", "auto",
           "hbst (binary descriptors), kdtree (fpfh), all (every older map; small sequences); "
           "auto: hbst or kdtree by the pipeline")
      .add("exact-retrieval", "", "",
           "HBST votes by the true nearest descriptor (backtracking) instead of one leaf")
      .add("gt-overlap", "F", "0.5", "true closure: occupancy overlap above F of the smaller map")
      .add("gt-max-distance", "M", "100", "true closure: anchors closer than M")
      .add("pose-tolerance", "M", "6", "correct closure: relative translation error under M")
      .add("loop-sigma-trans", "M", "0.5", "pose graph: loop edge translation sigma")
      .add("loop-sigma-rot-deg", "DEG", "2", "pose graph: loop edge rotation sigma")
      .add("dense-overlap", "F", "0",
           "dense check after the accept rule: ICP from the fitted motion, then accept only when "
           "the maps' occupied cells overlap by more than F of the smaller map (0 = off, the "
           "paper's setting)")
      .add("dense-cell", "M", "0.5", "dense check: overlap cell size")
      .add("dense-icp-voxel", "M", "0.5", "dense check: both maps voxelised for ICP")
      .add("dense-icp-distance", "M", "1", "dense check: ICP correspondence distance")
      .add("odometry-prior", "", "",
           "each candidate carries odometry's motion as a pose prior (drift-model sigmas of the "
           "travel between the maps): the pvalue rule's --prior-gate and jcbb's prior mode use it");
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
  c.scan_spacing = o.real("scan-spacing", 1e-3, 1e6);
  cli::read_rows(o, frontend_param_rows(), c.extract);
  c.lidar.beams = static_cast<int>(o.integer("lidar-beams", 1, 1024));
  c.lidar.columns = static_cast<int>(o.integer("lidar-columns", 1, 100000));
  c.lidar.max_range = o.real("lidar-max-range", 3.0, 1e4);
  c.lidar.range_noise = o.real("lidar-noise", 0.0, 10.0);
  c.lidar.dropout = o.real("lidar-dropout", 0.0, 0.99);
  c.world.building_density = o.real("world-building-density", 0.0, 1.0);
  c.world.kerb_density = o.real("world-kerb-density", 0.0, 1.0);
  c.odometry = o.text("odometry");
  if (c.odometry != "drift" && c.odometry != "gicp" && c.odometry != "poses" &&
      c.odometry != "log") {
    throw UsageError("--odometry: '" + c.odometry + "' is not drift, gicp, poses or log");
  }
  c.gicp.voxel = o.real("gicp-voxel", 0.01, 100.0);
  c.gicp.max_correspondence = o.real("gicp-max-distance", 0.01, 1000.0);
  c.gicp.map_scans = static_cast<int>(o.integer("gicp-map-scans", 1, 1000));
  c.drift.trans_rel = o.real("drift-trans", 0.0, 1.0);
  c.drift.yaw_deg = o.real("drift-yaw-deg", 0.0, 90.0);
  c.drift.tilt_deg = o.real("drift-tilt-deg", 0.0, 90.0);
  c.maps.map_length = o.real("map-length", 1.0, 1e6);
  c.maps.voxel = o.real("map-voxel", 0.01, 100.0);
  c.retrieval.min_map_gap = static_cast<int>(o.integer("min-map-gap", 1, 1 << 20));
  c.retrieval.candidates = static_cast<int>(o.integer("candidates", 1, 1 << 20));
  c.retrieval.min_votes = static_cast<int>(o.integer("min-votes", 1, 1 << 30));
  c.retrieval.exact = o.flag("exact-retrieval");
  c.retrieval.method = o.text("retrieval");
  c.gt_overlap = o.real("gt-overlap", 1e-6, 1.0);
  c.gt_max_distance = o.real("gt-max-distance", 1e-6, 1e9);
  c.pose_tolerance = o.real("pose-tolerance", 1e-6, 1e9);
  c.loop_sigma_trans = o.real("loop-sigma-trans", 1e-6, 1e6);
  c.odometry_prior = o.flag("odometry-prior");
  c.dense.min_overlap = o.real("dense-overlap", 0.0, 0.999);
  c.dense.cell = o.real("dense-cell", 1e-3, 1e3);
  c.dense.icp.voxel = o.real("dense-icp-voxel", 1e-3, 1e3);
  c.dense.icp.max_correspondence = o.real("dense-icp-distance", 1e-3, 1e3);
  c.loop_sigma_rot_deg = o.real("loop-sigma-rot-deg", 1e-6, 180.0);
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
               {"scan_spacing_m", c.scan_spacing},
               {"frontend", cli::rows_json(frontend_param_rows(), c.extract)},
               {"map_length_m", c.maps.map_length},
               {"map_voxel_m", c.maps.voxel},
               {"occupancy_voxel_m", c.maps.occupancy_voxel},
               {"min_map_gap", c.retrieval.min_map_gap},
               {"candidates", c.retrieval.candidates},
               {"min_votes", c.retrieval.min_votes},
               {"exact_retrieval", c.retrieval.exact},
               {"retrieval", c.retrieval.method},
               {"gt_overlap", c.gt_overlap},
               {"gt_max_distance_m", c.gt_max_distance},
               {"pose_tolerance_m", c.pose_tolerance},
               {"loop_sigma_trans_m", c.loop_sigma_trans},
               {"loop_sigma_rot_deg", c.loop_sigma_rot_deg},
               {"odometry_prior", c.odometry_prior},
               {"dense_check",
                {{"min_overlap", c.dense.min_overlap},
                 {"cell_m", c.dense.cell},
                 {"icp_voxel_m", c.dense.icp.voxel},
                 {"icp_max_distance_m", c.dense.icp.max_correspondence},
                 {"icp_max_iterations", c.dense.icp.max_iterations}}},
               {"odometry", c.odometry},
               {"gicp",
                {{"voxel_m", c.gicp.voxel},
                 {"max_correspondence_m", c.gicp.max_correspondence},
                 {"max_iterations", c.gicp.max_iterations},
                 {"map_scans", c.gicp.map_scans}}},
               {"drift",
                {{"trans_rel", c.drift.trans_rel},
                 {"yaw_deg_per_sqrt_m", c.drift.yaw_deg},
                 {"tilt_deg_per_sqrt_m", c.drift.tilt_deg}}},
               {"solvers", c.solvers}};
  if (!c.source) {
    p["loop"]["lidar"] = {{"beams", c.lidar.beams},
                          {"columns", c.lidar.columns},
                          {"fov_up_deg", c.lidar.fov_up_deg},
                          {"fov_down_deg", c.lidar.fov_down_deg},
                          {"min_range_m", c.lidar.min_range},
                          {"max_range_m", c.lidar.max_range},
                          {"range_noise_m", c.lidar.range_noise},
                          {"dropout", c.lidar.dropout}};
    p["loop"]["world"] = {{"road_half_width_m", c.world.road_half_width},
                          {"kerb_band_m", c.world.kerb_band},
                          {"building_setback_m", c.world.building_setback},
                          {"building_depth_m", c.world.building_depth},
                          {"building_density", c.world.building_density},
                          {"kerb_density", c.world.kerb_density},
                          {"sensor_height_m", c.world.sensor_height}};
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
