// KITTI odometry (Geiger et al., CVPR 2012; the odometry devkit's readme for
// data_odometry_{velodyne,calib,poses}; KISS-ICP python/kiss_icp/datasets/kitti.py reads it so):
//   DIR/velodyne/NNNNNN.bin  float32 x y z reflectance a point, little-endian
//   DIR/calib.txt            `Tr:` T_camera_velodyne, 12 numbers
//   DIR/times.txt            one stamp [s] a line, one per scan (optional)
//   poses                    DIR/poses.txt, or DIR/../../poses/NN.txt as the download unpacks
//                            (dataset/sequences/NN, dataset/poses/NN.txt); none for 11-21
// The poses are the left camera's (z forward); Tr^-1 * P * Tr makes them Velodyne poses in the
// first Velodyne frame (z up).
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "core/errors.hpp"
#include "loop/sources/common.hpp"

namespace verifybench::sources {
namespace {
namespace fs = std::filesystem;

const PointRecord kRecord{"KITTI: float32 x y z reflectance", 16};

// DIR/poses.txt, else the download layout's poses/NN.txt; "" when neither exists.
std::string find_poses(const fs::path& dir) {
  if (is_file((dir / "poses.txt").string())) return (dir / "poses.txt").string();
  fs::path seq = fs::absolute(dir).lexically_normal();
  if (!seq.has_filename()) seq = seq.parent_path();  // "DIR/"
  const fs::path official =
      seq.parent_path().parent_path() / "poses" / (seq.filename().string() + ".txt");
  return is_file(official.string()) ? official.string() : "";
}

std::vector<double> read_times(const std::string& path, std::size_t scans) {
  std::ifstream in(path);
  if (!in) input_error(path, 0, "cannot open");
  std::vector<double> stamps;
  long long line_no = 0;
  for (std::string line; std::getline(in, line);) {
    ++line_no;
    if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
    const ParsedReal t = parse_real_token(line.substr(0, line.find_last_not_of(" \t\r") + 1));
    if (t.error != NumberError::none) input_error(path, line_no, "'" + line + "' is not a stamp");
    if (!stamps.empty() && !(t.value > stamps.back())) {
      input_error(path, line_no, "stamp " + line + " is not after the previous one");
    }
    stamps.push_back(t.value);
  }
  if (stamps.size() != scans) {
    input_error(path, 0,
                std::to_string(stamps.size()) + " stamps for " + std::to_string(scans) + " scans");
  }
  return stamps;
}

std::unique_ptr<SequenceSource> open(const std::string& dir, const SourceOptions&) {
  const fs::path root(dir);
  const std::string velodyne = (root / "velodyne").string();
  require_dir(velodyne, "KITTI scans: DIR/velodyne/NNNNNN.bin");
  auto files = list_scans(velodyne, {".bin"});
  if (files.empty()) input_error(velodyne, 0, "no .bin scan");
  // Scans are numbered from 000000 without a gap: a missing one would shift every later pose.
  for (std::size_t i = 0; i < files.size(); ++i) {
    if (stem_integer(files[i]) != i) {
      char name[32];
      std::snprintf(name, sizeof name, "%06zu.bin", i);
      input_error((root / "velodyne" / name).string(), 0,
                  "no such scan (KITTI numbers its scans from 000000 without gaps; the next is " +
                      fs::path(files[i]).filename().string() + ")");
    }
  }

  SequenceInfo info;
  info.format = "kitti";
  info.dir = dir;
  info.recorded = static_cast<int>(files.size());
  const std::string times = (root / "times.txt").string();
  if (is_file(times)) {
    info.stamps = read_times(times, files.size());
  } else {
    for (std::size_t i = 0; i < files.size(); ++i) info.stamps.push_back(static_cast<double>(i));
    info.note = "no times.txt: stamps are scan indices";
  }
  info.poses_file = find_poses(root);
  if (!info.poses_file.empty()) {
    const std::string calib = (root / "calib.txt").string();
    require_file(calib, "its Tr: line turns the camera poses of " + info.poses_file +
                            " into Velodyne poses");
    info.poses = camera_to_velodyne(read_kitti_poses(info.poses_file), read_kitti_calib_tr(calib));
    if (info.poses.size() != files.size()) {
      input_error(info.poses_file, 0,
                  std::to_string(info.poses.size()) + " poses for " + std::to_string(files.size()) +
                      " scans in " + velodyne);
    }
  }
  return std::make_unique<FileSequence>(
      std::move(info), std::move(files),
      [](const std::string& file) { return read_records(file, kRecord); });
}

}  // namespace

SourceInfo kitti_source() {
  return {"kitti",
          "KITTI odometry: DIR/velodyne/NNNNNN.bin, DIR/calib.txt, poses in DIR/poses.txt or "
          "DIR/../../poses/NN.txt, DIR/times.txt",
          [](const std::string& dir) { return is_dir((fs::path(dir) / "velodyne").string()); },
          open};
}

}  // namespace verifybench::sources
