#include "loop/loop_report.hpp"

#include <sys/stat.h>

#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <iomanip>
#include <sstream>
#include <stdexcept>

#include "core/metrics.hpp"
#include "reports/report.hpp"

namespace verifybench {
namespace {

using json = nlohmann::json;

json number(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }

json ape_json(const ApeStats& a) {
  return {
      {"rmse", a.rmse}, {"mean", a.mean}, {"median", a.median}, {"max", a.max}, {"poses", a.poses}};
}

/// A relation error (loop/relations.hpp) as JSON; null where the run had no relations.
json relation_json(const LoopConfig& config, const RelationError& e) {
  if (config.relations.empty()) return nullptr;
  auto number = [](double v) { return std::isfinite(v) ? json(v) : json(nullptr); };
  return {{"relations", e.relations},
          {"used", e.used},
          {"translation_m", number(e.translation_m)},
          {"translation_sq_m2", number(e.translation_sq)},
          {"rotation_deg", number(e.rotation_deg)},
          {"rotation_sq_deg2", number(e.rotation_sq)}};
}

/// --odometry-calibration's estimate; null when it did not run.
json calibration_json(const OdometryCalibration& c) {
  if (!c.ran) return nullptr;
  return {{"yaw_rate_deg_per_m", c.yaw_rate_deg_per_m}, {"pairs", c.pairs},
          {"matched", c.matched},  {"kept", c.kept},
          {"travel_m", c.travel_m}, {"residual_deg_rms", c.residual_deg_rms},
          {"yaw_sigma_deg_per_sqrt_m", c.yaw_sigma_deg_per_sqrt_m}};
}

json score_json(const ClosureScore& s) {
  return {{"tp", s.tp},
          {"fp", s.fp},
          {"fn", s.fn},
          {"precision", number(s.precision)},
          {"recall", number(s.recall)},
          {"f1", number(s.f1)}};
}

json matrix_json(const Rigid<3>& T) {
  json rows = json::array();
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 4; ++j) rows.push_back(T.matrix()(i, j));
  }
  return rows;
}

json positions(const std::vector<Rigid<3>>& poses) {
  json out = json::array();
  for (const auto& T : poses) {
    const Eigen::Vector3d p = T.translation();
    out.push_back({std::round(p.x() * 1000) / 1000, std::round(p.y() * 1000) / 1000,
                   std::round(p.z() * 1000) / 1000});
  }
  return out;
}

std::string fixed(double v, int digits) {
  if (!std::isfinite(v)) return "-";
  std::ostringstream s;
  s << std::fixed << std::setprecision(digits) << v;
  return s.str();
}

void make_folder(const std::string& dir) {
  struct stat st {};
  if (::lstat(dir.c_str(), &st) == 0) {
    if (!S_ISDIR(st.st_mode)) {
      throw std::runtime_error("cannot write the loop report in " + dir +
                               ": it exists and is not a folder");
    }
    return;
  }
  // Missing parents are made too (--out out/k00 in a fresh checkout), as mkdir -p does.
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) throw std::runtime_error("cannot create " + dir + ": " + ec.message());
}

}  // namespace

json loop_report(const LoopConfig& config, const LoopRun& run, const json& context,
                 const json& parameters) {
  json maps = json::array();
  for (const MapInfo& m : run.maps) {
    maps.push_back(
        {{"index", m.index},
         {"first_frame", m.first_frame + config.first_frame},
         {"last_frame", m.last_frame + config.first_frame},
         {"anchor_frame", m.anchor + config.first_frame},
         {"scans", m.scans},
         {"points", m.points},
         {"keypoints", m.keypoints},
         {"occupied_cells", m.occupied_cells},
         {"position_truth", {m.position_truth.x(), m.position_truth.y(), m.position_truth.z()}}});
  }
  json truths = json::array();
  for (const TrueClosure& t : run.true_closures) {
    truths.push_back({{"query", t.query},
                      {"match", t.match},
                      {"overlap", t.overlap},
                      {"distance_m", t.distance}});
  }
  json closures = json::array();
  for (const ClosureRow& r : run.rows) {
    json row = to_json(r.record);
    row["query"] = r.query;
    row["match"] = r.match;
    row["votes"] = r.votes;
    row["overlap"] = r.overlap;
    row["true_closure"] = r.true_closure;
    row["correct"] = r.correct;
    row["closure_translation_error_m"] = r.translation_error;
    row["closure_rotation_error_deg"] = r.rotation_error_deg;
    row["T_match_query_estimate"] = matrix_json(r.T_estimate);
    row["T_match_query_truth"] = matrix_json(r.T_truth);
    row["rule_accepted"] = r.rule_accepted;
    row["loop_consistent"] = r.consistent ? nlohmann::json(*r.consistent) : nlohmann::json(nullptr);
    if (r.dense.ran) {
      row["dense_check"] = {
          {"overlap", r.dense.overlap},
          {"icp_converged", r.dense.icp.converged},
          {"icp_fitness_m2", r.dense.icp.fitness},
          {"refined_translation_error_m",
           (r.T_estimate.translation() - r.T_truth.translation()).norm()},
          {"refined_rotation_error_deg", rotation_error_deg<3>(r.T_estimate, r.T_truth)},
          {"T_match_query_refined", matrix_json(r.dense.icp.T_target_source)}};
    } else {
      row["dense_check"] = nullptr;
    }
    closures.push_back(row);
  }
  json summary = json::array(), curves = json::object();
  json trajectories = {{"truth", positions(run.truth)}, {"odometry", positions(run.odometry)}};
  json frames = json::array();
  for (int f : run.frames) frames.push_back(f + config.first_frame);
  trajectories["frames"] = frames;
  for (const SolverSummary& s : run.summary) {
    json row = {{"solver", s.solver},
                {"pipeline", config.extract.pipeline},
                {"closures_accepted", s.accepted},
                {"loop_edges", s.loop_edges},
                {"inliers_mean", s.inliers_mean},
                {"time_ms_mean", s.time_ms_mean},
                {"calibration_ms_mean", s.calibration_ms_mean},
                {"max_recall_full_precision", s.max_recall_full_precision},
                {"ape_without_m", run.ape_without.rmse},
                {"ape_with_m", s.ape_with.rmse},
                {"ape_with_robust_m", s.ape_with_robust.rmse},
                {"ape_without", ape_json(run.ape_without)},
                {"ape_with", ape_json(s.ape_with)},
                {"ape_with_robust", ape_json(s.ape_with_robust)},
                {"relation_error_without", relation_json(config, run.relations_without)},
                {"relation_error_with", relation_json(config, s.relations_with)},
                {"relation_error_with_robust", relation_json(config, s.relations_with_robust)},
                {"pose_graph",
                 {{"iterations", s.graph_iterations},
                  {"converged", s.graph_converged},
                  {"iterations_robust", s.graph_iterations_robust},
                  {"converged_robust", s.graph_converged_robust}}}};
    row.update(score_json(s.score));
    summary.push_back(row);
    json count = json::array(), alpha = json::array();
    for (const CurvePoint& p : s.count_curve) {
      json c = score_json(p.score);
      c["min_inliers"] = static_cast<int>(p.threshold);
      count.push_back(c);
    }
    for (const CurvePoint& p : s.alpha_curve) {
      json c = score_json(p.score);
      c["alpha"] = p.threshold;
      alpha.push_back(c);
    }
    curves[s.solver] = {{"count", count}, {"alpha", alpha}};
    trajectories[s.solver] = positions(s.poses_with);
    trajectories[s.solver + "+robust"] = positions(s.poses_with_robust);
  }
  json candidates = json::array();
  for (const Candidate& c : run.candidates) {
    candidates.push_back({{"query", c.query}, {"match", c.match}, {"votes", c.votes}});
  }
  return {{"schema_version", kLoopReportSchemaVersion},
          {"kind", "loop"},
          {"context", context},
          {"parameters", parameters},
          {"seconds", run.seconds},
          {"world", run.world},
          {"odometry_calibration", calibration_json(run.calibration)},
          {"maps", maps},
          {"true_closures", truths},
          {"candidates", candidates},
          {"closures", closures},
          {"summary", summary},
          {"curves", curves},
          {"trajectories", trajectories}};
}

std::string loop_markdown(const LoopConfig& config, const LoopRun& run) {
  std::ostringstream md;
  md << "# Loop closure: " << run.maps.size() << " local maps, " << run.true_closures.size()
     << " true closures, " << run.candidates.size() << " candidates (pipeline "
     << config.extract.pipeline << ", accept rule " << to_string(config.accept.rule)
     << ")\n\n";
  md << "Table I: loop-closure validation\n\n";
  md << "| solver | accepted | TP | FP | FN | precision | recall | F1 | max recall @ P=1 | "
        "inliers (mean) | time [ms] (mean) |\n";
  md << "|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const SolverSummary& s : run.summary) {
    md << "| " << s.solver << " | " << s.accepted << " | " << s.score.tp << " | " << s.score.fp
       << " | " << s.score.fn << " | " << fixed(s.score.precision, 3) << " | "
       << fixed(s.score.recall, 3) << " | " << fixed(s.score.f1, 3) << " | "
       << fixed(s.max_recall_full_precision, 3) << " | " << fixed(s.inliers_mean, 1) << " | "
       << fixed(s.time_ms_mean, 1) << " |\n";
  }
  md << "\nTable II: absolute trajectory error (APE rmse [m], SE(3)-aligned; " << run.truth.size()
     << " scans)\n\n";
  md << "| solver | without loops | with loops | with loops, robust (Cauchy) | loop edges |\n";
  md << "|---|---|---|---|---|\n";
  for (const SolverSummary& s : run.summary) {
    md << "| " << s.solver << " | " << fixed(run.ape_without.rmse, 2) << " | "
       << fixed(s.ape_with.rmse, 2) << " | " << fixed(s.ape_with_robust.rmse, 2) << " | "
       << s.loop_edges << " |\n";
  }
  if (!config.relations.empty()) {
    md << "\nRelation error (Kuemmerle et al. 2009: mean translation [m] / rotation [deg] of the "
       << run.relations_without.used << " of " << run.relations_without.relations
       << " reference relations in " << config.relations_file << ")\n\n";
    md << "| solver | without loops | with loops | with loops, robust (Cauchy) |\n";
    md << "|---|---|---|---|\n";
    auto cell = [](const RelationError& e) {
      return fixed(e.translation_m, 3) + " / " + fixed(e.rotation_deg, 2);
    };
    for (const SolverSummary& s : run.summary) {
      md << "| " << s.solver << " | " << cell(run.relations_without) << " | "
         << cell(s.relations_with) << " | " << cell(s.relations_with_robust) << " |\n";
    }
  }
  if (run.calibration.ran) {
    const OdometryCalibration& c = run.calibration;
    md << "\nOdometry calibration: " << fixed(c.yaw_rate_deg_per_m, 3)
       << " deg per metre of heading the odometry missed, added back (ICP matched " << c.matched << " of "
       << c.pairs << " consecutive scan pairs, " << c.kept << " kept over " << fixed(c.travel_m, 1)
       << " m; residual " << fixed(c.residual_deg_rms, 2) << " deg rms per pair, "
       << fixed(c.yaw_sigma_deg_per_sqrt_m, 2)
       << " deg / sqrt(m): the drift model's yaw sigma in this run)\n";
  }
  md << "\nWall time: " << fixed(run.seconds.count("total_s") ? run.seconds.at("total_s") : 0, 1)
     << " s\n";
  return md.str();
}

void check_loop_dir(const std::string& dir, bool overwrite) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (fs::is_directory(dir, ec) && !fs::is_empty(dir, ec)) {
    if (!overwrite) {
      throw std::runtime_error(dir +
                               " holds earlier results; pass --overwrite to replace them "
                               "(the folder is emptied first), or choose another folder");
    }
    if (!fs::exists(fs::path(dir) / "loop.json")) {
      throw std::runtime_error(
          "--overwrite empties only a loop output folder (one with loop.json); " + dir +
          " has none");
    }
  }
  make_folder(dir);
  check_report_path(dir + "/loop.json");
  check_report_path(dir + "/loop.md");
}

void clear_loop_dir(const std::string& dir) {
  namespace fs = std::filesystem;
  for (const auto& entry : fs::directory_iterator(dir)) fs::remove_all(entry.path());
}

void write_loop_trajectories(const std::string& dir, const LoopConfig& config, const LoopRun& run) {
  const std::string folder = dir + "/trajectories";
  make_folder(folder);
  std::vector<double> stamps;
  for (int f : run.frames) {
    stamps.push_back(config.stamps.empty() ? static_cast<double>(f + config.first_frame)
                                           : config.stamps[static_cast<std::size_t>(f)]);
  }
  write_tum_poses(folder + "/reference.tum", stamps, run.truth);
  write_tum_poses(folder + "/odometry.tum", stamps, run.odometry);
  for (const SolverSummary& s : run.summary) {
    write_tum_poses(folder + "/" + s.solver + ".tum", stamps, s.poses_with);
    write_tum_poses(folder + "/" + s.solver + "_robust.tum", stamps, s.poses_with_robust);
  }
}

void write_loop_report(const std::string& dir, const json& report, const std::string& markdown) {
  make_folder(dir);
  write_json_atomic(dir + "/loop.json", report);
  write_text_atomic(dir + "/loop.md", markdown);
}

}  // namespace verifybench
