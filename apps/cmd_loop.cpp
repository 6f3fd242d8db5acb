// `verifybench loop`: loop closure on a sequence (issue #14), simulated along a trajectory or on a
// KITTI-layout folder of scans; see loop/sequence.hpp.
#include <iostream>

#include "apps/cli.hpp"
#ifdef VERIFYBENCH_HAVE_LOOP
#include "harness/progress.hpp"
#include "loop/loop_report.hpp"
#endif

namespace verifybench {

#ifdef VERIFYBENCH_HAVE_LOOP
namespace {

void add_loop_options(Options& o) {
  o.group("sequence")
      .add("trajectory", "FILE", "",
           "KITTI poses (one row-major 3x4 a line): scans are simulated along it")
      .add("trajectory-frame", "F", "velodyne",
           "velodyne, or camera (KITTI odometry's poses.txt; needs --calib)")
      .add("calib", "FILE", "", "KITTI calib.txt whose `Tr:` line maps Velodyne into camera")
      .add("sequence", "DIR", "",
           "real scans: DIR/velodyne/NNNNNN.bin, DIR/poses.txt (camera frame), DIR/calib.txt")
      .add("first-frame", "I", "0", "first frame of the excerpt")
      .add("last-frame", "I", "-1", "last frame of the excerpt (-1 = the end)")
      .add("scan-spacing", "M", "2", "use a scan every M metres of travel")
      .add("pipeline", "3d|2d", "3d", "3d: ISS + B-SHOT on each map; 2d: bird's-eye view + ORB")
      .add("bev-range", "M", "80",
           "2d: half side of a map's bird's-eye image (ORB ignores a 15 m border: a 100 m map "
           "with 80 m of LiDAR range around it needs more than the 50 m of one scan)");
  o.group("simulated world and LiDAR (without --sequence)")
      .add("lidar-beams", "K", "64", "beams, evenly from +2 to -24.8 deg")
      .add("lidar-columns", "K", "1024", "azimuth steps a sweep")
      .add("lidar-max-range", "M", "80", "farthest return")
      .add("lidar-noise", "M", "0.02", "range noise sigma")
      .add("lidar-dropout", "P", "0.05", "probability of a lost return")
      .add("world-building-density", "P", "0.2", "chance of a building in a block cell")
      .add("world-kerb-density", "P", "0.45", "chance of a pole, tree, car or clutter in a kerb cell");
  o.group("odometry")
      .add("odometry", "drift|gicp", "drift",
           "drift: the drift model below on the true poses; gicp: PCL GICP of each scan to the "
           "last --gicp-map-scans scans")
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
      .add("exact-retrieval", "", "",
           "HBST votes by the true nearest descriptor (backtracking) instead of one leaf")
      .add("max-hamming", "BITS", "50", "HBST votes and matches within this distance")
      .add("matching", "POLICY", "nearest",
           "nearest, mutual, knn:K, or radius (every match within --max-hamming, as an HBST "
           "query returns them: the paper's setting)")
      .add("max-matches", "N", "5000", "cap a pair's correspondences (seeded; 0 = none)")
      .add("gt-overlap", "F", "0.5", "true closure: occupancy overlap above F of the smaller map")
      .add("gt-max-distance", "M", "100", "true closure: anchors closer than M")
      .add("pose-tolerance", "M", "6", "correct closure: relative translation error under M")
      .add("loop-sigma-trans", "M", "0.5", "pose graph: loop edge translation sigma")
      .add("loop-sigma-rot-deg", "DEG", "2", "pose graph: loop edge rotation sigma")
      .add("odometry-prior", "", "",
           "each candidate carries odometry's motion as a pose prior (drift-model sigmas of the "
           "travel between the maps): the pvalue rule's --prior-gate and jcbb's prior mode use it");
  cli::add_solver_options(o, {"1", "DIR", "report folder: loop.json and loop.md (required)"});
}

LoopConfig loop_config(const Options& o) {
  LoopConfig c;
  const bool has_trajectory = o.given("trajectory"), has_sequence = o.given("sequence");
  if (has_trajectory == has_sequence) {
    throw UsageError("give one of --trajectory FILE (simulated scans) or --sequence DIR");
  }
  Trajectory poses;
  std::string frame = o.text("trajectory-frame");
  std::string calib = o.text("calib");
  if (has_sequence) {
    c.sequence_dir = o.text("sequence");
    poses = read_kitti_poses(c.sequence_dir + "/poses.txt");
    if (!o.given("trajectory-frame")) frame = "camera";
    if (calib.empty()) calib = c.sequence_dir + "/calib.txt";
  } else {
    poses = read_kitti_poses(o.text("trajectory"));
  }
  if (frame == "camera") {
    if (calib.empty()) throw UsageError("--trajectory-frame camera needs --calib FILE");
    poses = camera_to_velodyne(poses, read_kitti_calib_tr(calib));
  } else if (frame != "velodyne") {
    throw UsageError("--trajectory-frame: '" + frame + "' is not velodyne or camera");
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
  c.first_frame = static_cast<int>(first);
  c.scan_spacing = o.real("scan-spacing", 1e-3, 1e6);
  c.extract.pipeline = o.text("pipeline");
  c.extract.p2.bev.range = o.real("bev-range", 1.0, 1e4);
  try {
    c.extract.matching = parse_matching(o.text("matching"));
  } catch (const std::invalid_argument& e) {
    throw UsageError(std::string("--matching: ") + e.what());
  }
  c.extract.max_hamming = static_cast<int>(o.integer("max-hamming", 0, 4096));
  c.extract.max_matches = static_cast<std::size_t>(o.integer("max-matches", 0, 1LL << 40));
  c.lidar.beams = static_cast<int>(o.integer("lidar-beams", 1, 1024));
  c.lidar.columns = static_cast<int>(o.integer("lidar-columns", 1, 100000));
  c.lidar.max_range = o.real("lidar-max-range", 3.0, 1e4);
  c.lidar.range_noise = o.real("lidar-noise", 0.0, 10.0);
  c.lidar.dropout = o.real("lidar-dropout", 0.0, 0.99);
  c.world.building_density = o.real("world-building-density", 0.0, 1.0);
  c.world.kerb_density = o.real("world-kerb-density", 0.0, 1.0);
  c.odometry = o.text("odometry");
  if (c.odometry != "drift" && c.odometry != "gicp") {
    throw UsageError("--odometry: '" + c.odometry + "' is not drift or gicp");
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
  c.gt_overlap = o.real("gt-overlap", 1e-6, 1.0);
  c.gt_max_distance = o.real("gt-max-distance", 1e-6, 1e9);
  c.pose_tolerance = o.real("pose-tolerance", 1e-6, 1e9);
  c.loop_sigma_trans = o.real("loop-sigma-trans", 1e-6, 1e6);
  c.odometry_prior = o.flag("odometry-prior");
  c.loop_sigma_rot_deg = o.real("loop-sigma-rot-deg", 1e-6, 180.0);
  c.solvers = cli::solver_names(o);
  c.params = cli::solver_params(o);
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
  nlohmann::json p = cli::params_json(c.params, cli::criteria(o));
  p["threads"] = c.threads;
  p["loop"] = {{"trajectory", o.text("trajectory")},
               {"sequence", c.sequence_dir},
               {"trajectory_frame", o.text("trajectory-frame")},
               {"first_frame", c.first_frame},
               {"frames", c.truth.size()},
               {"scan_spacing_m", c.scan_spacing},
               {"pipeline", c.extract.pipeline},
               {"bev_range_m", c.extract.p2.bev.range},
               {"map_length_m", c.maps.map_length},
               {"map_voxel_m", c.maps.voxel},
               {"occupancy_voxel_m", c.maps.occupancy_voxel},
               {"min_map_gap", c.retrieval.min_map_gap},
               {"candidates", c.retrieval.candidates},
               {"min_votes", c.retrieval.min_votes},
               {"exact_retrieval", c.retrieval.exact},
               {"max_hamming", c.extract.max_hamming},
               {"max_matches", c.extract.max_matches},
               {"matching", c.extract.matching.name()},
               {"gt_overlap", c.gt_overlap},
               {"gt_max_distance_m", c.gt_max_distance},
               {"pose_tolerance_m", c.pose_tolerance},
               {"loop_sigma_trans_m", c.loop_sigma_trans},
               {"loop_sigma_rot_deg", c.loop_sigma_rot_deg},
               {"odometry_prior", c.odometry_prior},
               {"odometry", c.odometry},
               {"gicp", {{"voxel_m", c.gicp.voxel},
                         {"max_correspondence_m", c.gicp.max_correspondence},
                         {"max_iterations", c.gicp.max_iterations},
                         {"map_scans", c.gicp.map_scans}}},
               {"drift", {{"trans_rel", c.drift.trans_rel},
                          {"yaw_deg_per_sqrt_m", c.drift.yaw_deg},
                          {"tilt_deg_per_sqrt_m", c.drift.tilt_deg}}},
               {"solvers", c.solvers}};
  if (c.sequence_dir.empty()) {
    p["loop"]["lidar"] = {{"beams", c.lidar.beams},           {"columns", c.lidar.columns},
                          {"fov_up_deg", c.lidar.fov_up_deg}, {"fov_down_deg", c.lidar.fov_down_deg},
                          {"min_range_m", c.lidar.min_range}, {"max_range_m", c.lidar.max_range},
                          {"range_noise_m", c.lidar.range_noise}, {"dropout", c.lidar.dropout}};
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

}  // namespace

int cmd_loop(const std::vector<std::string>& args, const std::vector<std::string>& argv) {
  Options o;
  add_loop_options(o);
  if (o.parse_or_help(args, "usage: verifybench loop (--trajectory FILE | --sequence DIR) "
                            "[options] --out DIR\n"))
    return 0;
  const LoopConfig config = loop_config(o);
  const std::string dir = o.required("out");
  try {
    check_loop_dir(dir);
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
  write_loop_report(dir, report, md);
  if (!quiet) std::cerr << md;
  std::cout << dir << "/loop.json\n";
  for (const ClosureRow& r : run.rows) {
    if (r.record.status == "error") {
      std::cerr << "verifybench: error: solver " << r.record.solver << " failed on maps "
                << r.query << " -> " << r.match << ": " << r.record.message << "\n";
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
