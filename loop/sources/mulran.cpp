// MulRan (Kim et al., ICRA 2020; https://sites.google.com/view/mulran-pr/dataset and its file
// player github.com/irapkaist/file_player_mulran; KISS-ICP python/kiss_icp/datasets/mulran.py):
//   DIR/Ouster/<ns stamp>.bin  float32 x y z intensity a point (Ouster OS1-64), little-endian
//   DIR/global_pose.csv        ns stamp, then T_world_base as 12 row-major numbers, comma-separated
//                              (UTM; more poses than scans)
// The poses are the vehicle base's: T_world_ouster = T_world_base * T_base_ouster, the extrinsic of
// MulRan's calib_base2ouster (x y z 1.7042 -0.021 1.8047 m, roll pitch yaw 0.0001 0.0003
// 179.6654 deg, as KISS-ICP's loader has it). Each scan takes the pose nearest its stamp, as
// KISS-ICP does, within kTolerance (scans farther from any pose are left out), and the world's
// origin moves to the first kept scan's position (UTM coordinates lose float precision).
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/errors.hpp"
#include "loop/sources/common.hpp"

namespace verifybench::sources {
namespace {
namespace fs = std::filesystem;

constexpr double kTolerance = 0.1;  // [s] one Ouster period
const PointRecord kRecord{"MulRan Ouster: float32 x y z intensity", 16};

Rigid<3> base_to_ouster() {
  constexpr double kDeg = M_PI / 180.0;
  return pose_xyz_rpy(1.7042, -0.021, 1.8047, 0.0001 * kDeg, 0.0003 * kDeg, 179.6654 * kDeg);
}

StampedTrajectory read_global_poses(const std::string& path) {
  std::ifstream in(path);
  if (!in) input_error(path, 0, "cannot open");
  StampedTrajectory out;
  long long line_no = 0;
  for (std::string line; std::getline(in, line);) {
    ++line_no;
    if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
    const std::vector<std::string> fields = csv_fields(line);
    if (fields.size() != 13) {
      input_error(path, line_no,
                  std::to_string(fields.size()) +
                      " fields; a MulRan pose is 13 (ns stamp, then 12 row-major numbers)");
    }
    const auto stamp = parse_unsigned_token(fields[0]);
    if (!stamp) input_error(path, line_no, "field 1 (stamp) '" + fields[0] + "' is not a ns stamp");
    const double t = static_cast<double>(*stamp) * 1e-9;
    if (!out.stamps.empty() && !(t > out.stamps.back())) {
      input_error(path, line_no, "field 1 (stamp) " + fields[0] + " is not after the previous");
    }
    out.stamps.push_back(t);
    out.poses.push_back(parse_row_major_pose({fields.begin() + 1, fields.end()}, path, line_no, 2));
  }
  if (out.poses.empty()) input_error(path, 0, "no pose");
  return out;
}

std::unique_ptr<SequenceSource> open(const std::string& dir, const SourceOptions&) {
  std::vector<std::string> files;
  SequenceInfo info = stamped_scans(dir, "Ouster", "MulRan scans: DIR/Ouster/<ns stamp>.bin", "mulran", 1e-9, files);

  info.poses_file = (fs::path(dir) / "global_pose.csv").string();
  require_file(info.poses_file, "MulRan ground truth");
  const StampedTrajectory base = read_global_poses(info.poses_file);
  std::vector<int> index;
  for (double t : info.stamps) index.push_back(nearest_stamp(base.stamps, t, kTolerance));
  Trajectory ouster_poses;
  const Rigid<3> extrinsic = base_to_ouster();
  for (const auto& T : base.poses) ouster_poses.push_back(T * extrinsic);
  keep_scans_with_pose(info, files, index, ouster_poses, "had no pose within 0.1 s");
  const Eigen::Vector3d origin = info.poses.front().translation();
  for (auto& T : info.poses) T.translation() -= origin;
  return std::make_unique<FileSequence>(
      std::move(info), std::move(files),
      [](const std::string& file) { return read_records(file, kRecord); });
}

}  // namespace

SourceInfo mulran_source() {
  return {"mulran", "MulRan: DIR/Ouster/<ns>.bin, DIR/global_pose.csv (base poses)",
          [](const std::string& dir) {
            return is_dir((fs::path(dir) / "Ouster").string()) &&
                   is_file((fs::path(dir) / "global_pose.csv").string());
          },
          open};
}

}  // namespace verifybench::sources
