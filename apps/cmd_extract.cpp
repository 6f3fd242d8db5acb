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
  Options o;
  o.group("scans")
      .add("source", "CLOUD", "", "source scan: KITTI .bin, .pcd or .ply (required)")
      .add("target", "CLOUD", "", "target scan (required)")
      .add("gt", "FILE", "", "T_target_source, 12 or 16 numbers row-major: labels the matches")
      .add("label-threshold", "M", "1", "label a match inlier when ||T m - q|| is under this")
      .add("seed", "S", "1", "seed of the --max-matches draw")
      .add("out", "DIR", "", "dump folder to create (required; must not exist)");
  o.group("front end (the same options as `verifybench loop`)");
  ExtractParams p;
  cli::add_rows(o, frontend_param_rows(), p);
  if (o.parse_or_help(args,
                      "usage: verifybench extract --source CLOUD --target CLOUD [--gt FILE] "
                      "[--pipeline 3d|2d|fpfh] --out DIR\n"))
    return 0;
  cli::read_rows(o, frontend_param_rows(), p);
  p.seed = o.seed("seed");
  p.label_threshold = o.real("label-threshold", 1e-9, 1e9);
  const std::string source = o.required("source"), target = o.required("target");
  const std::string out = o.required("out");
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
