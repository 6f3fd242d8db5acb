// NCLT (Carlevaris-Bianco et al., IJRR 2016; http://robots.engin.umich.edu/nclt/ and its
// read_vel_sync.py; KISS-ICP python/kiss_icp/datasets/nclt.py):
//   DIR/velodyne_sync/<utime>.bin  8-byte records: uint16 x y z, uint8 intensity, uint8 label,
//                                  little-endian; coordinate = value * 0.005 - 100 [m]
//   ground truth                   DIR/groundtruth_<date>.csv, or DIR/../ground_truth/
//                                  groundtruth_<DIR's name>.csv as KISS-ICP looks for it:
//                                  `utime, x, y, z, roll, pitch, yaw` of the Segway's body in a
//                                  local frame, R = Rz(yaw) Ry(pitch) Rx(roll); rows holding NaN
//                                  (the receiver's gaps) are skipped, as ct_icp's reader does
// The body and Velodyne frames are z down. Poses are T_world_body * T_body_velodyne, the
// extrinsic of the NCLT paper (x y z 0.002 -0.004 -0.957 m, roll pitch yaw 0.807 0.166 -90.703
// deg; ct_icp's kNCLT_Calib), and diag(1, -1, -1) on both sides turns points and poses z up, as
// KISS-ICP flips them. Each scan takes the nearest pose within kTolerance, as KISS-ICP takes the
// nearest; scans farther from any pose are left out.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/errors.hpp"
#include "loop/sources/common.hpp"

namespace verifybench::sources {
namespace {
namespace fs = std::filesystem;

constexpr double kTolerance = 0.1;  // [s] one Velodyne period
const PointRecord kRecord{
    "NCLT velodyne_sync: uint16 x y z, uint8 intensity label", 8, 0, 2, 4, true, 0.005, -100.0};
const char* const kFields[7] = {"utime", "x", "y", "z", "roll", "pitch", "yaw"};

Rigid<3> flip() {
  Rigid<3> F = Rigid<3>::Identity();
  F.linear() = Eigen::Vector3d(1, -1, -1).asDiagonal();
  return F;
}

Rigid<3> body_to_velodyne() {
  constexpr double kDeg = M_PI / 180.0;
  return pose_xyz_rpy(0.002, -0.004, -0.957, 0.807 * kDeg, 0.166 * kDeg, -90.703 * kDeg);
}

// DIR/groundtruth_*.csv (one), else KISS-ICP's place for it; "" when there is none.
std::string find_ground_truth(const fs::path& dir) {
  std::vector<std::string> found;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(dir, ec)) {
    const std::string name = e.path().filename().string();
    if (name.rfind("groundtruth_", 0) == 0 && e.path().extension() == ".csv") {
      found.push_back(e.path().string());
    }
  }
  if (found.size() > 1) input_error(dir.string(), 0, "several groundtruth_*.csv files");
  if (found.size() == 1) return found[0];
  fs::path seq = fs::absolute(dir).lexically_normal();
  if (!seq.has_filename()) seq = seq.parent_path();  // "DIR/"
  const fs::path kiss =
      seq.parent_path() / "ground_truth" / ("groundtruth_" + seq.filename().string() + ".csv");
  return is_file(kiss.string()) ? kiss.string() : "";
}

StampedTrajectory read_ground_truth(const std::string& path) {
  std::ifstream in(path);
  if (!in) input_error(path, 0, "cannot open");
  StampedTrajectory out;
  long long line_no = 0;
  for (std::string line; std::getline(in, line);) {
    ++line_no;
    if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
    const std::vector<std::string> fields = csv_fields(line);
    if (fields.size() != 7) {
      input_error(path, line_no,
                  std::to_string(fields.size()) +
                      " fields; an NCLT pose is 7 (utime, x, y, z, roll, pitch, yaw)");
    }
    double v[7];
    bool gap = false;
    for (int k = 0; k < 7; ++k) {
      const ParsedReal x = parse_real_token(fields[k]);
      gap = gap || (x.error == NumberError::not_finite && std::isnan(x.value));
      if (x.error != NumberError::none && !std::isnan(x.value)) {
        input_error(path, line_no,
                    "field " + std::to_string(k + 1) + " (" + kFields[k] + ") '" + fields[k] +
                        "' is not a finite number");
      }
      v[k] = x.value;
    }
    if (gap) continue;
    const double t = v[0] * 1e-6;
    if (!out.stamps.empty() && !(t > out.stamps.back())) {
      input_error(path, line_no, "field 1 (utime) " + fields[0] + " is not after the previous");
    }
    out.stamps.push_back(t);
    out.poses.push_back(pose_xyz_rpy(v[1], v[2], v[3], v[4], v[5], v[6]));
  }
  if (out.poses.empty()) input_error(path, 0, "no pose (every row empty or NaN)");
  return out;
}

std::unique_ptr<SequenceSource> open(const std::string& dir, const SourceOptions&) {
  std::vector<std::string> files;
  SequenceInfo info = stamped_scans(dir, "velodyne_sync", "NCLT scans: DIR/velodyne_sync/<utime>.bin", "nclt", 1e-6, files);

  info.poses_file = find_ground_truth(dir);
  if (!info.poses_file.empty()) {
    StampedTrajectory gt = read_ground_truth(info.poses_file);
    const Rigid<3> F = flip(), X = body_to_velodyne();
    for (auto& T : gt.poses) T = F * T * X * F;
    std::vector<int> index;
    for (double t : info.stamps) index.push_back(nearest_stamp(gt.stamps, t, kTolerance));
    keep_scans_with_pose(info, files, index, gt.poses, "had no ground truth within 0.1 s");
  }
  return std::make_unique<FileSequence>(std::move(info), std::move(files),
                                        [](const std::string& file) {
                                          Cloud cloud = read_records(file, kRecord);
                                          for (auto& p : cloud) p.tail<2>() = -p.tail<2>();
                                          return cloud;
                                        });
}

}  // namespace

SourceInfo nclt_source() {
  return {"nclt",
          "NCLT: DIR/velodyne_sync/<utime>.bin, DIR/groundtruth_<date>.csv (or "
          "DIR/../ground_truth/)",
          [](const std::string& dir) { return is_dir((fs::path(dir) / "velodyne_sync").string()); },
          open};
}

}  // namespace verifybench::sources
