// A folder of scans, as KISS-ICP's generic loader reads one (python/kiss_icp/datasets/generic.py:
// every point cloud file of the folder, natural order; .bin as KITTI records), plus a poses file:
//   DIR/*.pcd | *.ply | *.bin     (or the files of DIR's only subfolder holding any)
//   poses: SourceOptions::poses_file, else DIR/poses.txt, DIR/poses.tum or DIR/groundtruth.txt;
//          TUM (`timestamp tx ty tz qx qy qz qw`, TUM RGB-D's file_formats page) or KITTI
//          (12 numbers a line), told apart by the field count; taken as T_world_sensor as given
// Scans meet poses by stamp when the poses are TUM and every file stem is a number that falls
// within the poses' time span: a stem is seconds, or milli-, micro- or nanoseconds when its
// magnitude says so (>= 1e11, 1e14, 1e17: epoch times after 1973), and each scan takes the
// nearest pose within kTolerance. Otherwise by index, the counts equal.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>

#include "core/errors.hpp"
#include "frontend/cloud_io.hpp"
#include "loop/sources/common.hpp"

namespace verifybench::sources {
namespace {
namespace fs = std::filesystem;

constexpr double kTolerance = 0.05;  // [s] half a 10 Hz LiDAR period
const std::vector<std::string> kExtensions{".pcd", ".ply", ".bin"};
const PointRecord kBinRecord{"KITTI-style .bin: float32 x y z reflectance", 16};

// The stem as seconds, scaled by its magnitude; false when it is not a number.
bool stem_seconds(const std::string& file, double& seconds) {
  const ParsedReal v = parse_real_token(fs::path(file).stem().string());
  if (v.error != NumberError::none) return false;
  const double a = std::abs(v.value);
  seconds = v.value * (a >= 1e17 ? 1e-9 : a >= 1e14 ? 1e-6 : a >= 1e11 ? 1e-3 : 1.0);
  return true;
}

// DIR's scans, or those of its only subfolder holding any.
std::vector<std::string> find_scans(const std::string& dir) {
  auto files = list_scans(dir, kExtensions);
  if (!files.empty()) return files;
  std::vector<std::vector<std::string>> found;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(dir, ec)) {
    if (!e.is_directory(ec)) continue;
    auto sub = list_scans(e.path().string(), kExtensions);
    if (!sub.empty()) found.push_back(std::move(sub));
  }
  if (found.size() != 1) {
    input_error(dir, 0,
                found.empty() ? "no .pcd, .ply or .bin scan in the folder or a subfolder"
                              : "no scan in the folder and several subfolders hold scans");
  }
  return found[0];
}

std::string find_poses(const std::string& dir, const SourceOptions& options) {
  if (!options.poses_file.empty()) {
    require_file(options.poses_file, "SourceOptions::poses_file");
    return options.poses_file;
  }
  for (const char* name : {"poses.txt", "poses.tum", "groundtruth.txt"}) {
    const std::string p = (fs::path(dir) / name).string();
    if (is_file(p)) return p;
  }
  return "";
}

std::unique_ptr<SequenceSource> open(const std::string& dir, const SourceOptions& options) {
  require_dir(dir, "a folder of .pcd, .ply or .bin scans");
  auto files = find_scans(dir);
  SequenceInfo info;
  info.format = "folder";
  info.dir = dir;
  info.recorded = static_cast<int>(files.size());

  std::vector<double> file_stamps(files.size());
  bool stamped = true;
  for (std::size_t i = 0; i < files.size(); ++i) {
    stamped = stamped && stem_seconds(files[i], file_stamps[i]);
  }
  if (!stamped) {
    file_stamps.clear();
    for (std::size_t i = 0; i < files.size(); ++i) file_stamps.push_back(static_cast<double>(i));
  }
  info.stamps = file_stamps;
  info.poses_file = find_poses(dir, options);
  if (info.poses_file.empty()) {
    if (!stamped) info.note = "file names are not stamps: stamps are scan indices";
  } else {
    const StampedTrajectory poses = read_poses_file(info.poses_file);
    const bool tum = !poses.stamps.empty();
    const bool by_stamp = tum && stamped &&
                          file_stamps.front() >= poses.stamps.front() - kTolerance &&
                          file_stamps.back() <= poses.stamps.back() + kTolerance;
    if (by_stamp) {
      for (std::size_t i = 0; i < files.size(); ++i) {
        const int k = nearest_stamp(poses.stamps, file_stamps[i], kTolerance);
        if (k < 0) {
          input_error(files[i], 0,
                      "no pose of " + info.poses_file + " within " + std::to_string(kTolerance) +
                          " s of the scan's stamp " + std::to_string(file_stamps[i]) + " s");
        }
        info.poses.push_back(poses.poses[static_cast<std::size_t>(k)]);
      }
      info.note = "poses matched to scans by the stamps in the file names";
    } else {
      if (poses.poses.size() != files.size()) {
        input_error(info.poses_file, 0,
                    std::to_string(poses.poses.size()) + " poses for " +
                        std::to_string(files.size()) + " scans in " + dir +
                        " (matched by index: the file names are not stamps within the poses' "
                        "time span)");
      }
      info.poses = poses.poses;
      if (tum) info.stamps = poses.stamps;
      info.note = "poses matched to scans by index";
    }
  }
  return std::make_unique<FileSequence>(
      std::move(info), std::move(files), [](const std::string& file) {
        std::string ext = fs::path(file).extension().string();
        for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
        if (ext == ".bin") return read_records(file, kBinRecord);
        Cloud cloud = read_cloud(file);
        cloud.erase(std::remove_if(cloud.begin(), cloud.end(),
                                   [](const Eigen::Vector3f& p) { return p.isZero(0.0f); }),
                    cloud.end());
        return cloud;
      });
}

}  // namespace

SourceInfo folder_source() {
  return {"folder",
          "a folder of .pcd/.ply/.bin scans in name (or stamp) order, poses from a TUM or KITTI "
          "file (DIR/poses.txt, poses.tum, groundtruth.txt or the poses_file option)",
          [](const std::string& dir) {
            try {
              return is_dir(dir) && !list_scans(dir, kExtensions).empty();
            } catch (const InputError&) {
              return false;  // an unreadable folder is no layout
            }
          },
          open};
}

}  // namespace verifybench::sources
