// `verifybench extract`: a correspondence dump from two scans (ISS + B-SHOT, or BEV + ORB).
#include <filesystem>
#include <optional>

#include "apps/cli.hpp"
#ifdef VERIFYBENCH_HAVE_FRONTEND
#include "apps/param_options.hpp"
#include "frontend/extract.hpp"
#include "frontend/params.hpp"
#endif

namespace verifybench {

#ifdef VERIFYBENCH_HAVE_FRONTEND
int cmd_extract(const std::vector<std::string>& args) {
  ExtractParams p;
  std::string source, target, gt_file, out;
  Options o;
  o.group("scans")
      .text("source", source, "CLOUD", "source scan: KITTI .bin, .pcd or .ply (required)")
      .text("target", target, "CLOUD", "target scan (required)")
      .text("gt", gt_file, "FILE",
            "T_target_source, 12 or 16 numbers row-major: labels the matches")
      .real("label-threshold", p.label_threshold, "M",
            "label a match inlier when ||T m - q|| is under this", 1e-9, 1e9)
      .seed("seed", p.seed, "seed of the --max-matches draw")
      .text("out", out, "DIR", "dump folder to create (required; must not exist)")
      .flag("keep-clouds", p.keep_clouds,
            "keep both clouds in the dump (source_cloud.bin, target_cloud.bin) for run's dense "
            "check of an accepted motion (the default)")
      .flag("no-clouds", "leave the clouds out (a dump of the matches alone; run then decides "
            "by the accept rule only)", [&p] { p.keep_clouds = false; })
      .real("cloud-voxel", p.cloud_voxel, "M",
            "kept clouds: one point per cell of this grid (0 = every point as read)", 0.0, 1e3);
  o.group("front end (the same options as `verifybench loop`)");
  cli::add_rows(o, frontend_param_rows(), p);
  if (o.parse_or_help(args,
                      "usage: verifybench extract --source CLOUD --target CLOUD [--gt FILE] "
                      "[--pipeline 3d|2d|fpfh] --out DIR\n"))
    return 0;
  o.require("source");
  o.require("target");
  o.require("out");
  {  // refused before the work, as every command does (exit code 2)
    const std::filesystem::path target(out);
    const std::filesystem::path parent = target.has_parent_path() ? target.parent_path() : ".";
    if (std::filesystem::exists(target)) {
      throw UsageError("--out: dump folder " + out + " exists; remove it or choose another");
    }
    if (!std::filesystem::is_directory(parent)) {
      throw UsageError("--out: cannot write dump " + out + ": no folder " + parent.string());
    }
  }
  std::optional<std::string> gt;
  if (o.given("gt")) gt = gt_file;
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
