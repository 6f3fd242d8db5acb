// verifybench: command-line front end. list | sweep | run; see `verifybench --help`.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <tuple>
#include <variant>

#include "harness/builtin.hpp"
#include "harness/harness.hpp"
#include "apps/options.hpp"
#include "frontend/extract.hpp"
#include "datasets/dimacs.hpp"
#include "datasets/text_dump.hpp"
#include "reports/report.hpp"
#include "cliques/max_clique.hpp"
#include "solvers/registry.hpp"
#include "core/timer.hpp"

namespace vb = verifybench;
using nlohmann::json;

namespace {

const char* kUsage =
    "usage: verifybench <command> [options]\n"
    "commands:\n"
    "  list     registered solvers, generators and clique algorithms\n"
    "  sweep    robustness sweep on synthetic sets (success rate and time vs outlier ratio)\n"
    "  run      solvers on a correspondence dump (DIR/dump.json + matches.tsv, or DIR/corr.txt)\n"
    "  dimacs   maximum clique algorithms on DIMACS graphs (FILE.clq ...)\n"
    "  extract  a correspondence dump from two scans (ISS + B-SHOT, or BEV + ORB; HBST matching)\n"
    "`verifybench <command> --help` lists a command's options.\n";

void add_solver_options(vb::Options& o) {
  o.add("solvers", "A,B", "clique,ransac", "solvers to run (see `verifybench list`)")
      .add("eps", "M", "0.1", "pair length tolerance of the correspondence graph, Eq. (1) [m]")
      .add("inlier-threshold", "M", "", "RANSAC residual threshold [m] (default: eps)")
      .add("min-inliers", "K", "0",
           "accept when inliers >= K; 0 = paper default (5 in 3D, 10 in 2D)")
      .add("time-limit", "S", "60", "per-solve time limit [s]; best-so-far returned past it")
      .add("ransac-iterations", "K", "10000", "RANSAC iterations (cap when adaptive)")
      .add("ransac-adaptive", "", "", "RANSAC: adaptive iteration count")
      .add("ransac-confidence", "P", "0.999", "RANSAC: confidence of the adaptive count")
      .add("max-graph-mb", "MB", "4096", "refuse correspondence graphs larger than this")
      .add("threads", "T", "1",
           "threads for graph construction and clique-bbmc-dec (0 = all cores); results do not "
           "depend on it")
      .add("mac-max-cliques", "K", "1000000", "mac: stop enumerating maximal cliques after K")
      .add("mac-min-clique", "K", "3", "mac: smallest maximal clique that makes a hypothesis")
      .add("jcbb-sigma", "M", "0",
           "jcbb: per-axis point noise sigma [m] (0 = inlier threshold / 3)")
      .add("jcbb-confidence", "P", "0.95", "jcbb: level of the chi-square gates")
      .add("success-rot-deg", "DEG", "15", "success: rotation error under this [deg]")
      .add("success-trans", "M", "0.3", "success: translation error under this [m]")
      .add("seed", "S", "1", "seed of every random draw (recorded in the report)")
      .add("out", "FILE.json", "", "report path (required; written atomically)")
      .add("quiet", "", "", "no progress lines");
}

vb::SolverParams solver_params(const vb::Options& o) {
  vb::SolverParams p;
  p.eps = o.real("eps", 1e-12, 1e12);
  p.inlier_threshold =
      o.given("inlier-threshold") ? o.real("inlier-threshold", 1e-12, 1e12) : p.eps;
  p.min_inliers = static_cast<int>(o.integer("min-inliers", 0, 1 << 30));
  p.time_limit_s = o.real("time-limit", 1e-6, 1e9);
  p.ransac_iterations = static_cast<int>(o.integer("ransac-iterations", 1, 2000000000));
  p.ransac_adaptive = o.flag("ransac-adaptive");
  p.ransac_confidence = o.real("ransac-confidence", 1e-9, 1 - 1e-12);
  p.max_graph_bytes = static_cast<std::size_t>(o.integer("max-graph-mb", 1, 1LL << 30)) << 20;
  p.seed = o.seed("seed");
  p.threads = static_cast<int>(o.integer("threads", 0, 1024));
  p.mac_max_cliques = o.integer("mac-max-cliques", 1, 1LL << 62);
  p.mac_min_clique = static_cast<int>(o.integer("mac-min-clique", 2, 1 << 30));
  p.jcbb_sigma = o.real("jcbb-sigma", 0.0, 1e9);
  p.jcbb_confidence = o.real("jcbb-confidence", 1e-9, 1 - 1e-12);
  p.validate();
  return p;
}

vb::SuccessCriteria criteria(const vb::Options& o) {
  vb::SuccessCriteria c;
  c.max_rotation_error_deg = o.real("success-rot-deg", 0, 180);
  c.max_translation_error = o.real("success-trans", 0, 1e12);
  return c;
}

std::vector<std::string> solver_names(const vb::Options& o) {
  auto names = o.list("solvers");
  for (const auto& n : names) {
    if (!vb::SolverRegistry::contains(n)) vb::SolverRegistry::create(n);  // throws with the list
  }
  return names;
}

json params_json(const vb::SolverParams& p, const vb::SuccessCriteria& c) {
  return {{"eps", p.eps},
          {"inlier_threshold", p.inlier_threshold},
          {"min_inliers", p.min_inliers},
          {"accept_threshold_2d", p.accept_threshold(2)},
          {"accept_threshold_3d", p.accept_threshold(3)},
          {"time_limit_s", p.time_limit_s},
          {"ransac_iterations", p.ransac_iterations},
          {"ransac_adaptive", p.ransac_adaptive},
          {"ransac_confidence", p.ransac_confidence},
          {"max_graph_bytes", p.max_graph_bytes},
          {"threads", p.threads},
          {"mac_max_cliques", p.mac_max_cliques},
          {"mac_min_clique", p.mac_min_clique},
          {"jcbb_sigma", p.jcbb_point_sigma()},
          {"jcbb_confidence", p.jcbb_confidence},
          {"success_criteria",
           {{"max_rotation_error_deg", c.max_rotation_error_deg},
            {"max_translation_error", c.max_translation_error},
            {"requires_accepted", c.requires_accepted}}}};
}

void print_point(const std::vector<vb::TrialRecord>& rows) {
  for (const auto& a : vb::aggregate(rows)) {
    std::fprintf(stderr, "  %dD n=%d outliers=%s %-8s success=%s accept=%.2f median=%.2f ms\n",
                 a["dim"].get<int>(), a["n"].get<int>(), a["outlier_ratio"].dump().c_str(),
                 a["solver"].get<std::string>().c_str(), a["success_rate"].dump().c_str(),
                 a["accept_rate"].get<double>(),
                 a["median_time_ms"].is_null() ? 0.0 : a["median_time_ms"].get<double>());
  }
}

/// Writes the report; returns 1 when a solver reported an error (its message printed), else 0.
int finish(const std::string& out, const json& parameters, const std::vector<vb::TrialRecord>& rows,
           const std::vector<std::string>& argv, std::uint64_t seed) {
  vb::write_json_atomic(out, vb::make_report(vb::make_context(argv, seed), parameters, rows));
  std::cout << out << "\n";
  for (const auto& r : rows) {
    if (r.status == "error") {
      std::cerr << "verifybench: error: solver " << r.solver << " failed: " << r.message << "\n";
      return 1;
    }
  }
  return 0;
}

int cmd_list() {
  std::printf("solvers (sweep, run --solvers):\n");
  for (const auto& info : vb::SolverRegistry::list()) {
    std::printf("  %-18s %s\n", info.name.c_str(), info.description.c_str());
  }
  std::printf("generators (sweep --generator):\n");
  for (const auto& g : vb::list_generators()) {
    std::printf("  %-18s %s%s\n", g.name.c_str(), g.description.c_str(),
                g.supports_3d ? "" : " [2D only]");
  }
  std::printf("clique algorithms (dimacs --algorithms; solver clique-<name>):\n");
  for (const auto& info : vb::CliqueAlgorithms::list()) {
    std::printf("  %-18s %s%s\n", info.name.c_str(), info.description.c_str(),
                info.exact ? "" : " [heuristic]");
  }
  return 0;
}

int cmd_dimacs(const std::vector<std::string>& args, const std::vector<std::string>& argv) {
  vb::Options o;
  o.allow_positional("FILE.clq")
      .add("algorithms", "A,B", vb::kDefaultCliqueAlgorithm,
           "clique algorithms (see `verifybench list`)")
      .add("time-limit", "S", "60", "per-search time limit [s]")
      .add("threads", "T", "1", "threads of the parallel algorithms (bbmc-dec; 0 = all cores)")
      .add("seed", "S", "1", "seed of the randomised algorithms (bbmcx-ls; recorded in the report)")
      .add("max-graph-mb", "MB", "4096", "refuse graphs larger than this")
      .add("out", "FILE.json", "", "report path (required; written atomically)")
      .add("quiet", "", "", "no progress lines");
  o.parse(args);
  if (o.help_requested()) {
    std::cout << "usage: verifybench dimacs FILE.clq... [options] --out FILE.json\n"
                 "Known clique numbers are taken from MANIFEST.tsv beside each file when present.\n"
              << o.help();
    return 0;
  }
  if (o.positional().empty()) throw vb::UsageError("no DIMACS file given");
  const auto names = o.list("algorithms");
  for (const auto& n : names) vb::CliqueAlgorithms::get(n);  // throws with the known names
  vb::CliqueSearchParams params;
  params.time_limit_s = o.real("time-limit", 1e-6, 1e9);
  params.threads = static_cast<int>(o.integer("threads", 0, 1024));
  params.seed = o.seed("seed");
  const std::size_t max_bytes = static_cast<std::size_t>(o.integer("max-graph-mb", 1, 1LL << 30))
                                << 20;
  const std::string out = o.required("out");

  std::vector<vb::CliqueRecord> rows;
  for (const std::string& file : o.positional()) {
    const vb::BitGraph g = vb::read_dimacs(file, max_bytes);
    const std::filesystem::path path(file);
    std::optional<int> known;
    const auto manifest = path.parent_path() / "MANIFEST.tsv";
    if (std::filesystem::exists(manifest)) {
      const auto omega = vb::read_manifest(manifest.string());
      const auto it = omega.find(path.stem().string());
      if (it != omega.end()) known = it->second;
    }
    for (const auto& name : names) {
      const auto& algorithm = vb::CliqueAlgorithms::get(name);
      vb::CliqueRecord r;
      r.graph = file;
      r.algorithm = name;
      r.n = g.size();
      r.edges = g.edge_count();
      r.known_omega = known;
      try {
        vb::StopWatch clock;
        const vb::CliqueSearchResult res = algorithm.run(g, params);
        r.time_ms = clock.ms();
        r.status = res.stopped ? "time_limit" : res.optimal ? "ok" : "unproven";
        r.omega = static_cast<int>(res.clique.size());
        r.nodes = res.nodes;
        r.upper_bound = res.upper_bound;
        r.local_search_steps = res.local_search_steps;
        for (int v : res.clique) r.clique.push_back(v + 1);
        if (!g.is_clique(res.clique)) {
          r.status = "error";
          r.message = "the returned vertex set is not a clique";
        }
      } catch (const std::exception& e) {
        r.status = "error";
        r.message = e.what();
      }
      if (!o.flag("quiet")) {
        std::fprintf(stderr, "  %-28s %-12s omega=%-4d known=%-4s %-10s %10.2f ms\n",
                     path.filename().c_str(), name.c_str(), r.omega,
                     known ? std::to_string(*known).c_str() : "-", r.status.c_str(), r.time_ms);
      }
      rows.push_back(std::move(r));
    }
  }
  json parameters = {{"mode", "dimacs"},
                     {"algorithms", names},
                     {"time_limit_s", params.time_limit_s},
                     {"threads", params.threads}};
  vb::write_json_atomic(out, vb::make_report(vb::make_context(argv, params.seed), parameters, rows));
  std::cout << out << "\n";
  for (const auto& r : rows) {
    if (r.status == "error") {
      std::cerr << "verifybench: error: " << r.algorithm << " on " << r.graph << ": " << r.message
                << "\n";
      return 1;
    }
  }
  return 0;
}

/// --prior-rot-deg / --prior-trans: both > 0 or both 0 (no prior); sigmas in radians and metres.
std::pair<double, double> prior_sigmas(const vb::Options& o) {
  const double rot = o.real("prior-rot-deg", 0.0, 180.0) * M_PI / 180.0;
  const double trans = o.real("prior-trans", 0.0, 1e9);
  if ((rot > 0.0) != (trans > 0.0)) {
    throw vb::UsageError("--prior-rot-deg and --prior-trans go together (both > 0)");
  }
  return {rot, trans};
}

void add_prior_options(vb::Options& o, const char* what) {
  o.add("prior-rot-deg", "DEG", "0",
        std::string("give ") + what +
            " a pose prior drawn around the truth: rotation sigma per "
            "axis [deg] (with --prior-trans; jcbb uses it)")
      .add("prior-trans", "M", "0", "pose prior translation sigma per axis [m]");
}

/// Refuses an unknown generator or one that lacks a requested dimension, before any work.
void check_generator(const std::string& kind, const std::vector<int>& dims) {
  std::string known;
  for (const auto& g : vb::list_generators()) {
    known += (known.empty() ? "" : ", ") + g.name;
    if (g.name != kind) continue;
    for (int d : dims) {
      if ((d == 2 && !g.supports_2d) || (d == 3 && !g.supports_3d)) {
        throw vb::UsageError("--generator " + kind + " does not exist in " + std::to_string(d) +
                             "D");
      }
    }
    return;
  }
  throw vb::UsageError("--generator: unknown kind '" + kind + "' (known: " + known + ")");
}

int cmd_sweep(const std::vector<std::string>& args, const std::vector<std::string>& argv) {
  vb::Options o;
  add_solver_options(o);
  o.add("dim", "D", "3", "dimension: 2, 3 or 2,3")
      .add("n", "N", "500", "correspondences per set")
      .add("outliers", "RANGE", "0.5:0.99:0.05",
           "outlier ratios: start:stop:step (stop included) or a,b,c")
      .add("noise", "SIGMA", "0.01", "Gaussian noise per axis on inlier targets [m]")
      .add("extent", "M", "10", "side of the cube (square) the points are drawn in [m]")
      .add("trials", "K", "20", "sets per (dim, outlier ratio) point")
      .add("generator", "KIND", "uniform", "synthetic generator (see `verifybench list`)")
      .add("group-ratio", "R", "0.5", "rigid-group: wrong group size / inlier count")
      .add("grid-spacing", "M", "2", "repetitive: pillar spacing along the corridor [m]")
      .add("overlap", "F", "0.3", "partial-overlap: fraction of the scene holding the inliers")
      .add("tail-dof", "NU", "3", "heavy-tailed: Student-t degrees of freedom")
      .add("anisotropy", "A", "5", "anisotropic: noise along the sensor ray / across it")
      .add("near-radius", "M", "1", "near-true, bev-orb: outliers this far from the truth [m]")
      .add("cell", "M", "0.5", "bev-orb: bird's-eye-view cell size [m]")
      .add("score-separation", "D", "1",
           "match scores N(D * label, 1), inliers higher (prosac's order); < 0 = none");
  add_prior_options(o, "each set");
  o.parse(args);
  if (o.help_requested()) {
    std::cout << "usage: verifybench sweep [options] --out FILE.json\n" << o.help();
    return 0;
  }
  vb::SweepConfig c;
  c.solvers = solver_names(o);
  c.dims.clear();
  for (const auto& d : o.list("dim")) {
    if (d != "2" && d != "3") throw vb::UsageError("--dim: '" + d + "' is not 2 or 3");
    c.dims.push_back(d == "2" ? 2 : 3);
  }
  c.n = static_cast<int>(o.integer("n", 1, 100000000));
  c.outlier_ratios = vb::parse_range("--outliers", o.text("outliers"), 0.0, 1.0);
  c.noise = o.real("noise", 0.0, 1e9);
  c.extent = o.real("extent", 1e-9, 1e9);
  c.trials = static_cast<int>(o.integer("trials", 1, 1000000));
  c.shape.kind = o.text("generator");
  c.shape.group_ratio = o.real("group-ratio", 1e-9, 1e9);
  c.shape.grid_spacing = o.real("grid-spacing", 1e-9, 1e9);
  c.shape.overlap = o.real("overlap", 1e-9, 1.0);
  c.shape.tail_dof = o.real("tail-dof", 1e-9, 1e9);
  c.shape.anisotropy = o.real("anisotropy", 1.0, 1e9);
  c.shape.near_radius = o.real("near-radius", 1e-9, 1e9);
  c.shape.cell = o.real("cell", 1e-9, 1e9);
  c.shape.score_separation = o.real("score-separation", -1e9, 1e9);
  check_generator(c.shape.kind, c.dims);
  std::tie(c.prior_sigma_rot, c.prior_sigma_trans) = prior_sigmas(o);
  c.params = solver_params(o);
  c.seed = c.params.seed;
  c.criteria = criteria(o);
  const std::string out = o.required("out");

  json parameters = params_json(c.params, c.criteria);
  parameters["sweep"] = {{"generator", c.shape.kind},
                         {"generator_shape",
                          {{"group_ratio", c.shape.group_ratio},
                           {"grid_spacing", c.shape.grid_spacing},
                           {"overlap", c.shape.overlap},
                           {"tail_dof", c.shape.tail_dof},
                           {"anisotropy", c.shape.anisotropy},
                           {"near_radius", c.shape.near_radius},
                           {"cell", c.shape.cell},
                           {"score_separation", c.shape.score_separation}}},
                         {"prior_sigma_rot_deg", c.prior_sigma_rot * 180.0 / M_PI},
                         {"prior_sigma_trans", c.prior_sigma_trans},
                         {"dims", c.dims},
                         {"n", c.n},
                         {"outlier_ratios", c.outlier_ratios},
                         {"noise", c.noise},
                         {"extent", c.extent},
                         {"trials", c.trials},
                         {"solvers", c.solvers}};
  vb::SweepProgress progress;
  if (!o.flag("quiet")) progress = print_point;
  const auto rows = vb::run_sweep(c, progress);
  return finish(out, parameters, rows, argv, c.seed);
}

int cmd_run(const std::vector<std::string>& args, const std::vector<std::string>& argv) {
  vb::Options o;
  o.add("dump", "DIR", "",
        "dump folder: dump.json + matches.tsv, or corr.txt [label.txt] [GTmat.txt] (required)");
  add_solver_options(o);
  o.add("trials", "K", "1", "repeat each solver K times (timing statistics)");
  add_prior_options(o, "the set (it needs a ground truth)");
  o.parse(args);
  if (o.help_requested()) {
    std::cout << "usage: verifybench run --dump DIR [options] --out FILE.json\n" << o.help();
    return 0;
  }
  const std::string dir = o.required("dump");
  const auto names = solver_names(o);
  const vb::SolverParams params = solver_params(o);
  const vb::SuccessCriteria crit = criteria(o);
  const int trials = static_cast<int>(o.integer("trials", 1, 1000000));
  const std::string out = o.required("out");
  const auto [prior_rot, prior_trans] = prior_sigmas(o);
  vb::Dump dump = vb::read_dump(dir);
  std::vector<vb::TrialRecord> rows = std::visit(
      [&](auto& s) {
        vb::validate(s);
        if (prior_rot > 0.0) {
          if (!s.truth.T_target_source) {
            throw vb::UsageError("--prior-rot-deg: " + dir +
                                 " has no ground truth to draw a prior around");
          }
          vb::add_pose_prior(s, prior_rot, prior_trans, params.seed);
        }
        return vb::run_on_set(names, s, dir, trials, params.seed, params, crit);
      },
      dump.set);
  if (!o.flag("quiet")) print_point(rows);
  json parameters = params_json(params, crit);
  parameters["run"] = {
      {"dump", dir},
      {"trials", trials},
      {"prior_sigma_rot_deg", prior_rot * 180.0 / M_PI},
      {"prior_sigma_trans", prior_trans},
      {"solvers", names},
      {"label_threshold", dump.label_threshold ? json(*dump.label_threshold) : json(nullptr)},
      {"dump_provenance", dump.provenance}};
  return finish(out, parameters, rows, argv, params.seed);
}

int cmd_extract(const std::vector<std::string>& args) {
  vb::Options o;
  o.add("source", "CLOUD", "", "source scan: KITTI .bin, .pcd or .ply (required)")
      .add("target", "CLOUD", "", "target scan (required)")
      .add("gt", "FILE", "", "T_target_source, 12 or 16 numbers row-major: labels the matches")
      .add("pipeline", "3d|2d", "3d", "3d: ISS + B-SHOT; 2d: bird's-eye view + ORB")
      .add("voxel", "M", "0.5", "3d: voxel grid leaf")
      .add("iss-salient-radius", "M", "3", "3d: ISS salient radius")
      .add("iss-non-max-radius", "M", "2", "3d: ISS non-maximum radius")
      .add("iss-gamma", "G", "0.975", "3d: ISS eigenvalue ratio thresholds (gamma21 = gamma32)")
      .add("iss-min-neighbors", "K", "5", "3d: ISS minimum neighbours")
      .add("normal-radius", "M", "1", "3d: normal estimation radius")
      .add("shot-radius", "M", "2", "3d: SHOT support radius")
      .add("cell", "M", "0.5", "2d: bird's-eye-view cell size")
      .add("min-occupancy", "F", "0.05", "2d: drop cells under this fraction of the maximum")
      .add("range", "M", "50", "2d: imaged half side around the sensor")
      .add("orb-features", "K", "1000", "2d: most ORB keypoints")
      .add("max-hamming", "BITS", "50", "keep matches within this Hamming distance")
      .add("exact-matching", "", "", "HBST with backtracking (exact nearest) instead of one leaf")
      .add("hbst-leaf", "K", "64", "HBST: most descriptors per leaf")
      .add("label-threshold", "M", "1", "label a match inlier when ||T m - q|| is under this")
      .add("out", "DIR", "", "dump folder to create (required; must not exist)");
  o.parse(args);
  if (o.help_requested()) {
    std::cout << "usage: verifybench extract --source CLOUD --target CLOUD [--gt FILE] --out DIR\n"
              << o.help();
    return 0;
  }
  vb::ExtractParams p;
  p.pipeline = o.text("pipeline");
  if (p.pipeline != "3d" && p.pipeline != "2d") {
    throw vb::UsageError("--pipeline: '" + p.pipeline + "' is not 3d or 2d");
  }
  p.p3.voxel = o.real("voxel", 1e-6, 1e6);
  p.p3.salient_radius = o.real("iss-salient-radius", 1e-6, 1e6);
  p.p3.non_max_radius = o.real("iss-non-max-radius", 1e-6, 1e6);
  p.p3.gamma21 = p.p3.gamma32 = o.real("iss-gamma", 1e-6, 1.0);
  p.p3.min_neighbors = static_cast<int>(o.integer("iss-min-neighbors", 1, 1 << 20));
  p.p3.normal_radius = o.real("normal-radius", 1e-6, 1e6);
  p.p3.shot_radius = o.real("shot-radius", 1e-6, 1e6);
  p.p2.bev.cell = o.real("cell", 1e-6, 1e6);
  p.p2.bev.min_fraction = o.real("min-occupancy", 0.0, 1.0);
  p.p2.bev.range = o.real("range", 1e-6, 1e6);
  p.p2.orb_features = static_cast<int>(o.integer("orb-features", 1, 1 << 24));
  p.max_hamming = static_cast<int>(o.integer("max-hamming", 0, 1 << 20));
  p.exact_matching = o.flag("exact-matching");
  p.hbst.max_leaf_size = static_cast<int>(o.integer("hbst-leaf", 1, 1 << 24));
  p.label_threshold = o.real("label-threshold", 1e-9, 1e9);
  const std::string source = o.required("source"), target = o.required("target");
  const std::string out = o.required("out");
  std::optional<std::string> gt;
  if (o.given("gt")) gt = o.text("gt");
  const vb::Dump dump = vb::extract(source, target, gt, p);
  vb::write_dump(out, dump);
  const auto& c = dump.provenance["counts"];
  std::cerr << "  keypoints " << c["source"].value("keypoints", 0.0) << " / "
            << c["target"].value("keypoints", 0.0) << ", descriptors "
            << c["source"].value("descriptors", 0.0) << " / "
            << c["target"].value("descriptors", 0.0) << ", matches " << c["matches"] << "\n";
  std::cout << out << "\n";
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  const std::vector<std::string> all(argv, argv + argc);
  vb::register_builtin_solvers();
  vb::register_clique_algorithms();
  if (argc < 2) {
    std::cerr << "verifybench: error: no command given\n" << kUsage;
    return 2;
  }
  if (all[1] == "--help" || all[1] == "-h" || all[1] == "help") {
    std::cout << kUsage;
    return 0;
  }
  const std::string cmd = all[1];
  const std::vector<std::string> rest(all.begin() + 2, all.end());
  try {
    if (cmd == "list") {
      vb::Options o;
      o.parse(rest);
      if (o.help_requested()) {
        std::cout << "usage: verifybench list\n" << o.help();
        return 0;
      }
      return cmd_list();
    }
    if (cmd == "sweep") return cmd_sweep(rest, all);
    if (cmd == "run") return cmd_run(rest, all);
    if (cmd == "dimacs") return cmd_dimacs(rest, all);
    if (cmd == "extract") return cmd_extract(rest);
    throw vb::UsageError("unknown command '" + cmd +
                         "' (commands: list, sweep, run, dimacs, extract)");
  } catch (const vb::UsageError& e) {  // bad command line
    std::cerr << "verifybench: error: " << e.what() << "\n";
  } catch (const vb::InputError& e) {  // malformed input file
    std::cerr << "verifybench: error: " << e.what() << "\n";
  } catch (const std::invalid_argument& e) {  // unknown solver, invalid parameter or set
    std::cerr << "verifybench: error: " << e.what() << "\n";
  } catch (const std::exception& e) {  // could not write the report, out of memory, ...
    std::cerr << "verifybench: error: " << e.what() << "\n";
    return 1;
  }
  return 2;
}
