// `verifybench extract`: a correspondence dump from two scans (ISS + B-SHOT, or BEV + ORB).
#include <optional>

#include "apps/cli.hpp"
#ifdef VERIFYBENCH_HAVE_FRONTEND
#include "frontend/extract.hpp"
#endif

namespace verifybench {

#ifdef VERIFYBENCH_HAVE_FRONTEND
int cmd_extract(const std::vector<std::string>& args) {
  Options o;
  o.add("source", "CLOUD", "", "source scan: KITTI .bin, .pcd or .ply (required)")
      .add("target", "CLOUD", "", "target scan (required)")
      .add("gt", "FILE", "", "T_target_source, 12 or 16 numbers row-major: labels the matches")
      .add("pipeline", "3d|2d|fpfh", "3d",
           "3d: ISS + B-SHOT; 2d: bird's-eye view + ORB; fpfh: voxel centroids + FPFH")
      .add("voxel", "M", "0.5", "3d, fpfh: voxel grid leaf (fpfh: 0.3 unless given)")
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
      .add("fpfh-normal-radius", "M", "0", "fpfh: normal estimation radius (0 = 2 x voxel)")
      .add("fpfh-radius", "M", "0", "fpfh: FPFH support radius (0 = 5 x voxel)")
      .add("matching", "POLICY", "nearest",
           "nearest | mutual | knn:K | radius (every match within the distance limit)")
      .add("max-hamming", "BITS", "50", "keep matches within this Hamming distance")
      .add("max-matches", "N", "0",
           "cap the dump at N rows: whole source keypoints in a seeded random order (0 = none)")
      .add("seed", "S", "1", "seed of the --max-matches draw")
      .add("max-feature-distance", "D", "inf",
           "fpfh: keep matches within this feature-space distance (radius needs it)")
      .add("exact-matching", "", "", "HBST with backtracking (exact nearest) instead of one leaf")
      .add("hbst-leaf", "K", "64", "HBST: most descriptors per leaf")
      .add("label-threshold", "M", "1", "label a match inlier when ||T m - q|| is under this")
      .add("out", "DIR", "", "dump folder to create (required; must not exist)");
  if (o.parse_or_help(
          args, "usage: verifybench extract --source CLOUD --target CLOUD [--gt FILE] --out DIR\n"))
    return 0;
  ExtractParams p;
  p.pipeline = o.text("pipeline");
  std::string names;
  bool known = false;
  for (const auto& info : list_pipelines()) {
    names += (names.empty() ? "" : " or ") + info.name;
    known = known || info.name == p.pipeline;
  }
  if (!known) throw UsageError("--pipeline: '" + p.pipeline + "' is not " + names);
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
  p.pf.voxel = o.given("voxel") ? p.p3.voxel : 0.3;
  p.pf.normal_radius = o.real("fpfh-normal-radius", 0.0, 1e6);
  p.pf.fpfh_radius = o.real("fpfh-radius", 0.0, 1e6);
  try {
    p.matching = parse_matching(o.text("matching"));
  } catch (const std::invalid_argument& e) {
    throw UsageError(std::string("--matching: ") + e.what());
  }
  if (o.text("max-feature-distance") != "inf") {
    p.max_feature_distance = o.real("max-feature-distance", 0.0, 1e12);
  }
  p.max_hamming = static_cast<int>(o.integer("max-hamming", 0, 1 << 20));
  p.max_matches = static_cast<std::size_t>(o.integer("max-matches", 0, 1LL << 40));
  p.seed = o.seed("seed");
  p.exact_matching = o.flag("exact-matching");
  p.hbst.max_leaf_size = static_cast<int>(o.integer("hbst-leaf", 1, 1 << 24));
  p.label_threshold = o.real("label-threshold", 1e-9, 1e9);
  const std::string source = o.required("source"), target = o.required("target");
  const std::string out = o.required("out");
  std::optional<std::string> gt;
  if (o.given("gt")) gt = o.text("gt");
  const Dump dump = extract(source, target, gt, p);
  write_dump(out, dump);
  const auto& c = dump.provenance["counts"];
  std::cerr << "  keypoints " << c["source"].value("keypoints", 0.0) << " / "
            << c["target"].value("keypoints", 0.0) << ", descriptors "
            << c["source"].value("descriptors", 0.0) << " / "
            << c["target"].value("descriptors", 0.0) << ", matches " << c["matches"] << "\n";
  std::cout << out << "\n";
  return 0;
}
#else
int cmd_extract(const std::vector<std::string>&) {
  throw UsageError(
      "extract: this build has no front end (configure with VERIFYBENCH_WITH_PCL=ON and "
      "VERIFYBENCH_WITH_OPENCV=ON)");
}
#endif

}  // namespace verifybench
