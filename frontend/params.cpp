#include "frontend/params.hpp"

#include <sstream>

namespace verifybench {

namespace {

using Row = ParamRow<ExtractParams>;
using Kind = Row::Kind;
constexpr double kBig = 1e6;  // [m] the largest radius or range a row takes

Row real(std::string option, std::string key, std::string value_name, std::string help,
         double min, double max) {
  Row r;
  r.option = std::move(option);
  r.key = std::move(key);
  r.value_name = std::move(value_name);
  r.help = std::move(help);
  r.kind = Kind::real;
  r.min = min;
  r.max = max;
  return r;
}

Row integer(std::string option, std::string key, std::string value_name, std::string help,
            double min, double max) {
  Row r = real(std::move(option), std::move(key), std::move(value_name), std::move(help), min, max);
  r.kind = Kind::integer;
  return r;
}

std::string pipeline_names(const std::string& separator) {
  std::string names;
  for (const auto& info : list_pipelines()) names += (names.empty() ? "" : separator) + info.name;
  return names;
}

std::vector<Row> make_rows() {
  std::vector<Row> rows;
  Row pipeline;
  pipeline.option = "pipeline";
  pipeline.key = "pipeline";
  pipeline.value_name = pipeline_names("|");
  pipeline.help = "3d: ISS + B-SHOT; 2d: bird's-eye view + ORB; fpfh: voxel centroids + FPFH";
  pipeline.kind = Kind::text;
  pipeline.get_text = [](const ExtractParams& p) { return p.pipeline; };
  pipeline.set_text = [](ExtractParams& p, const std::string& v) {
    for (const auto& info : list_pipelines()) {
      if (info.name == v) {
        p.pipeline = v;
        return;
      }
    }
    throw std::invalid_argument("'" + v + "' is not " + pipeline_names(" or "));
  };
  rows.push_back(pipeline);

  // --voxel sets the leaf of whichever voxel pipeline runs (3d and fpfh keep their own defaults).
  Row voxel = real("voxel", "voxel_m", "M", "3d, fpfh: voxel grid leaf", 1e-6, kBig);
  voxel.get = [](const ExtractParams& p) {
    return p.pipeline == "fpfh" ? p.pf.voxel : p.p3.voxel;
  };
  voxel.set = [](ExtractParams& p, double v) { p.p3.voxel = p.pf.voxel = v; };
  voxel.get_text = [](const ExtractParams& p) {
    std::ostringstream out;
    out << p.p3.voxel << "; fpfh " << p.pf.voxel;
    return out.str();
  };
  rows.push_back(voxel);
  rows.push_back(param_row(&ExtractParams::p3, &Pipeline3dParams::salient_radius,
                           real("iss-salient-radius", "iss_salient_radius_m", "M",
                                "3d: ISS salient radius", 1e-6, kBig)));
  rows.push_back(param_row(&ExtractParams::p3, &Pipeline3dParams::non_max_radius,
                           real("iss-non-max-radius", "iss_non_max_radius_m", "M",
                                "3d: ISS non-maximum radius", 1e-6, kBig)));
  Row gamma = real("iss-gamma", "iss_gamma", "G",
                   "3d: ISS eigenvalue ratio thresholds (gamma21 = gamma32)", 1e-6, 1.0);
  gamma.get = [](const ExtractParams& p) { return p.p3.gamma21; };
  gamma.set = [](ExtractParams& p, double v) { p.p3.gamma21 = p.p3.gamma32 = v; };
  rows.push_back(gamma);
  rows.push_back(param_row(&ExtractParams::p3, &Pipeline3dParams::min_neighbors,
                           integer("iss-min-neighbors", "iss_min_neighbors", "K",
                                   "3d: ISS minimum neighbours", 1, 1 << 20)));
  rows.push_back(param_row(&ExtractParams::p3, &Pipeline3dParams::normal_radius,
                           real("normal-radius", "normal_radius_m", "M",
                                "3d: normal estimation radius", 1e-6, kBig)));
  rows.push_back(param_row(&ExtractParams::p3, &Pipeline3dParams::shot_radius,
                           real("shot-radius", "shot_radius_m", "M", "3d: SHOT support radius",
                                1e-6, kBig)));

  Row cell = real("cell", "bev_cell_m", "M", "2d: bird's-eye-view cell size", 1e-6, kBig);
  cell.get = [](const ExtractParams& p) { return p.p2.bev.cell; };
  cell.set = [](ExtractParams& p, double v) { p.p2.bev.cell = v; };
  rows.push_back(cell);
  Row occupancy = real("min-occupancy", "bev_min_occupancy", "F",
                       "2d: drop cells under this fraction of the maximum", 0.0, 1.0);
  occupancy.get = [](const ExtractParams& p) { return p.p2.bev.min_fraction; };
  occupancy.set = [](ExtractParams& p, double v) { p.p2.bev.min_fraction = v; };
  rows.push_back(occupancy);
  Row range = real("range", "bev_range_m", "M",
                   "2d: imaged half side around the scan's (or map's) origin; ORB ignores a "
                   "31-cell border",
                   1e-6, kBig);
  range.get = [](const ExtractParams& p) { return p.p2.bev.range; };
  range.set = [](ExtractParams& p, double v) { p.p2.bev.range = v; };
  rows.push_back(range);
  rows.push_back(param_row(&ExtractParams::p2, &Pipeline2dParams::orb_features,
                           integer("orb-features", "orb_features", "K", "2d: most ORB keypoints",
                                   1, 1 << 24)));

  rows.push_back(param_row(&ExtractParams::pf, &PipelineFpfhParams::normal_radius,
                           real("fpfh-normal-radius", "fpfh_normal_radius_m", "M",
                                "fpfh: normal estimation radius (0 = 2 x voxel)", 0.0, kBig)));
  rows.push_back(param_row(&ExtractParams::pf, &PipelineFpfhParams::fpfh_radius,
                           real("fpfh-radius", "fpfh_radius_m", "M",
                                "fpfh: FPFH support radius (0 = 5 x voxel)", 0.0, kBig)));
  rows.push_back(param_row(
      &ExtractParams::pf, &PipelineFpfhParams::skip_horizontal_deg,
      real("fpfh-skip-horizontal", "fpfh_skip_horizontal_deg", "DEG",
           "fpfh: no keypoints whose normal is within DEG of the z axis (ground, ceilings; 0 = "
           "keep all)",
           0.0, 90.0)));

  Row matching;
  matching.option = "matching";
  matching.key = "matching";
  matching.value_name = "POLICY";
  matching.help =
      "nearest | mutual | knn:K | radius (every match within the distance limit) | ratio:R (the "
      "nearest when closer than R x the second: Lowe's test)";
  matching.kind = Kind::text;
  matching.get_text = [](const ExtractParams& p) { return p.matching.name(); };
  matching.set_text = [](ExtractParams& p, const std::string& v) { p.matching = parse_matching(v); };
  rows.push_back(matching);
  rows.push_back(param_row(&ExtractParams::max_hamming,
                           integer("max-hamming", "max_hamming", "BITS",
                                   "binary descriptors: keep matches within this Hamming distance",
                                   0, 4096)));
  Row feature_distance =
      real("max-feature-distance", "max_feature_distance", "D",
           "fpfh: keep matches within this feature-space distance (radius needs it)", 0.0, 1e12);
  feature_distance.infinite_ok = true;
  rows.push_back(param_row(&ExtractParams::max_feature_distance, feature_distance));
  rows.push_back(param_row(&ExtractParams::max_matches,
                           integer("max-matches", "max_matches", "N",
                                   "cap a pair's matches at N rows: whole source keypoints in a "
                                   "seeded random order (0 = none)",
                                   0, 1e12)));
  Row exact = integer("exact-matching", "exact_matching", "",
                      "HBST with backtracking (exact nearest) instead of one leaf", 0, 1);
  exact.kind = Kind::flag;
  rows.push_back(param_row(&ExtractParams::exact_matching, exact));
  rows.push_back(param_row(&ExtractParams::hbst, &HbstParams::max_leaf_size,
                           integer("hbst-leaf", "hbst_leaf", "K", "HBST: most descriptors per leaf",
                                   1, 1 << 24)));
  return rows;
}

}  // namespace

const std::vector<ParamRow<ExtractParams>>& frontend_param_rows() {
  static const std::vector<ParamRow<ExtractParams>> rows = make_rows();
  return rows;
}

}  // namespace verifybench
